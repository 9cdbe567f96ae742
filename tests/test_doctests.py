"""The Examples sections of the docstrings run and print what they show."""

import doctest

import pytest

from thermocontact import api
from thermocontact.problem import axes, materials, units
from thermocontact.solvers import single_patch


@pytest.mark.parametrize("module", [single_patch, units, materials, axes, api],
                         ids=lambda m: m.__name__)
def test_docstring_examples(module):
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0 and result.failed == 0
