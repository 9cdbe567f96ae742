"""Computations run in lockstep (execution.lockstep): each gets the answers it would
get alone, the requests of a round are answered together, and a failure ends them all."""

import threading

import pytest

from thermocontact.execution.lockstep import run_lockstep


def _collatz(start):
    """A computation of its own length: asks for ``3x + 1`` or ``x/2`` until 1."""
    def run(ask):
        x, path = start, [start]
        while x != 1:
            x = ask("odd" if x % 2 else "even", x)
            path.append(x)
        return path
    return run


def _answer(calls):
    def evaluate(key, payloads):
        calls.append((key, list(payloads)))
        return [3 * x + 1 if key == "odd" else x // 2 for x in payloads]
    return evaluate


def _alone(start):
    x, path = start, [start]
    while x != 1:
        x = 3 * x + 1 if x % 2 else x // 2
        path.append(x)
    return path


def test_each_gets_its_own_answers_and_rounds_are_batched():
    starts = [6, 7, 1, 27, 12]
    calls, told = [], []
    got = run_lockstep([_collatz(s) for s in starts], _answer(calls),
                       lambda i, result: told.append((i, result[-1])))
    assert got == [_alone(s) for s in starts]
    # Every request answered once, in batches: one call per kind per round, the
    # longest computation setting the number of rounds.
    assert sum(len(p) for _, p in calls) == sum(len(_alone(s)) - 1 for s in starts)
    rounds = max(len(_alone(s)) - 1 for s in starts)
    assert rounds <= len(calls) <= 2 * rounds
    assert max(len(p) for _, p in calls) > 1
    assert sorted(told) == [(i, 1) for i in range(len(starts))]
    # Short computations are told first (they end in earlier rounds).
    assert told[0][0] == 2 and told[-1][0] == 3


def test_a_failure_ends_every_computation_and_is_raised():
    before = threading.active_count()

    def fails(ask):
        ask("even", 4)
        raise ValueError("broken")

    with pytest.raises(ValueError, match="broken"):
        run_lockstep([_collatz(27), fails, _collatz(97)], _answer([]))
    assert threading.active_count() == before

    def wrong(key, payloads):
        raise RuntimeError("evaluation failed")

    with pytest.raises(RuntimeError, match="evaluation failed"):
        run_lockstep([_collatz(27), _collatz(5)], wrong)
    assert threading.active_count() == before


def test_no_computations():
    assert run_lockstep([], _answer([])) == []
