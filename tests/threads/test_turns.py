"""``ThreadCtx.turns`` (the iterator a transpiled loop takes its checkpoints from) counts a slice
exactly as the integer it replaced: a reference model of that integer and the real thread record
go through the same random operations and must agree on every budget read and every slow path."""

from __future__ import annotations

import random

import pytest

from gplrt.threads.scheduler import ThreadCtx


class _Sched:
    """What ThreadCtx needs of a scheduler: the slice size and a slow path that records itself."""

    def __init__(self, size: int) -> None:
        self.slice_checkpoints = size
        self.slow: list[int] = []
        self.abort_at: int | None = None

    def _checkpoint_slow(self, ctx: ThreadCtx) -> None:
        self.slow.append(len(self.slow))
        ctx.budget = self.slice_checkpoints
        if self.abort_at == len(self.slow):
            raise RuntimeError("abort")


class _Model:
    """The old integer budget: ``budget -= 1; if budget <= 0: slow path (budget = size)``."""

    def __init__(self, size: int) -> None:
        self.size = size
        self.budget = size
        self.slow = 0

    def checkpoint(self) -> None:
        self.budget -= 1
        if self.budget <= 0:
            self.slow += 1
            self.budget = self.size


@pytest.mark.parametrize("seed", range(20))
def test_turns_count_a_slice_like_the_integer_they_replaced(seed: int) -> None:
    rng = random.Random(seed)
    size = rng.choice([1, 2, 3, 10, 1000])
    sched = _Sched(size)
    ctx = ThreadCtx(name="t", sched=sched)  # type: ignore[arg-type]
    model = _Model(size)
    for _ in range(3000):
        op = rng.random()
        if op < 0.8:
            next(ctx.turns)
            model.checkpoint()
        elif op < 0.9:  # Thread.Sleep(0) charges part of the slice
            cost = rng.randint(1, size)
            ctx.budget -= cost
            model.budget -= cost
            if model.budget <= 0:  # the scheduler ends the slice itself (not a checkpoint)
                ctx.budget = size
                model.budget = size
        else:  # a request forces the next checkpoint onto the slow path
            ctx.budget = 0
            model.budget = 0
        assert ctx.budget == model.budget
        assert len(sched.slow) == model.slow


def test_a_slow_path_that_raises_leaves_fresh_turns_with_the_budget_it_set() -> None:
    sched = _Sched(4)
    sched.abort_at = 1
    ctx = ThreadCtx(name="t", sched=sched)  # type: ignore[arg-type]
    dead = ctx.turns
    for _ in range(3):
        next(dead)
    with pytest.raises(RuntimeError):
        next(dead)  # the fourth checkpoint ends the slice; its slow path raises
    assert next(dead, "ended") == "ended"  # chain is dead once its source raised
    assert ctx.turns is not dead and ctx.budget == 4
    for _ in range(3):
        next(ctx.turns)
    assert len(sched.slow) == 1
    next(ctx.turns)
    assert len(sched.slow) == 2 and ctx.budget == 4
