"""thermocontact: steady thermoelastic sliding contact with frictional heating.

A heat-conducting elastic cylinder slides over a stationary heat-conducting elastic
half-plane; frictional heat distorts both surfaces.  :func:`solve` (or
:class:`Model` for many solves that share an assembly) returns the contact's load
ratio, offset, heat partition, pressure and heat-flux distributions and the
validity of the single-patch solution.

The names below are imported on first use, so that ``import thermocontact`` (and
the command line's start) costs nothing until NumPy and SciPy are needed.
"""

from importlib import import_module

from ._version import __version__

#: Public name -> module that defines it.
_EXPORTS = {
    "Axis": ".problem.axes",
    "BulkTemperatures": ".problem.closure",
    "FarTemperatures": ".problem.closure",
    "HeatPartition": ".problem.closure",
    "Offset": ".problem.closure",
    "boundary": ".api",
    "contact": ".api",
    "compute_map": ".api",
    "contact_set": ".api",
    "map_spec": ".api",
    "operating_map": ".api",
    "parameter_map": ".api",
    "Validity": ".analysis.validity",
    "Applicability": ".analysis.applicability",
    "ContactFields": ".analysis.fields",
    "Material": ".problem.materials",
    "PhysicalConductance": ".problem.conductance",
    "PhysicalProblem": ".problem.physical",
    "Branch": ".studies.physical_contact",
    "PhysicalContact": ".studies.physical_contact",
    "ContactSetResult": ".studies.contact_sets",
    "PhysicalContactSet": ".studies.contact_sets",
    "ZoneSolution": ".solvers.zones",
    "Event": ".studies.boundaries",
    "Path": ".studies.boundaries",
    "MapSpec": ".studies.maps",
    "OperatingSpec": ".studies.operating_maps",
    "TEIMode": ".studies.tei",
    "TEIResult": ".studies.tei",
    "DEFAULT_METHOD": ".discretisation.methods",
    "METHODS": ".discretisation.methods",
    "Method": ".discretisation.methods",
    "clear_caches": ".numerics.cache",
    "ConvergenceWarning": ".problem.errors",
    "Error": ".problem.errors",
    "ExecutionError": ".problem.errors",
    "FileError": ".problem.errors",
    "InputError": ".problem.errors",
    "MaterialError": ".problem.materials",
    "NotConvergedError": ".problem.errors",
    "Parameters": ".problem.parameters",
    "SolveError": ".problem.errors",
    "ContactSolution": ".solvers.result",
    "Model": ".solvers.single_patch",
    "solve": ".solvers.single_patch",
    "stability": ".api",
    "StabilityResult": ".solvers.stability",
    "tei": ".api",
    "transient": ".api",
    "transient_spec": ".api",
    "compute_transient": ".api",
    "read_transient": ".api",
    "contact_transient": ".api",
    "contact_transient_spec": ".api",
    "TransientRun": ".solvers.transient",
    "TransientSpec": ".solvers.transient",
}

__all__ = sorted(_EXPORTS) + ["__version__"]

#: The public names in groups, as the API reference shows them (each name in one group;
#: tested).
GROUPS = {
    "Solve a contact": ["solve", "Model", "contact", "contact_set", "stability"],
    "Follow and map": ["boundary", "parameter_map", "operating_map", "map_spec",
                       "compute_map", "Axis"],
    "In time, and its instability": ["transient", "transient_spec", "compute_transient",
                                     "read_transient", "contact_transient",
                                     "contact_transient_spec", "tei"],
    "The closure": ["HeatPartition", "Offset", "FarTemperatures", "BulkTemperatures"],
    "The problem": ["Material", "PhysicalProblem", "Parameters", "PhysicalConductance",
                    "MapSpec", "OperatingSpec", "TransientSpec"],
    "Results": ["ContactSolution", "PhysicalContact", "Branch", "ContactSetResult",
                "PhysicalContactSet", "ZoneSolution", "Path", "Event", "StabilityResult",
                "TEIResult", "TEIMode", "TransientRun", "Validity", "Applicability",
                "ContactFields"],
    "Errors and warnings": ["Error", "InputError", "MaterialError", "FileError",
                            "SolveError", "NotConvergedError", "ExecutionError",
                            "ConvergenceWarning"],
    "Methods and caches": ["METHODS", "Method", "DEFAULT_METHOD", "clear_caches",
                           "__version__"],
}


def __getattr__(name):
    if name in _EXPORTS:
        value = getattr(import_module(_EXPORTS[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'thermocontact' has no attribute {name!r}")


def __dir__():
    return __all__
