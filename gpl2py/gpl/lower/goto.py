"""Where GoTo jumps go: the block structure of a procedure, and which blocks need a dispatch loop.

Lowering keeps procedures structured; only a statement list that a GoTo must enter somewhere other
than at its start becomes a dispatch loop (docs/design/lowering.md, "GoTo").  This module computes,
per procedure:

* the parent and *role* of every block (``body``, ``try``, ``catch``, ``finally``, ``loop``,
  ``branch``) and the statement that owns it;
* per block, the statements where a segment of its dispatch loop starts (targeted labels, and
  statements a GoTo enters from outside -- see below);
* per GoTo, a :class:`Jump`: the dispatch loop to restart, the segment to set in every block on
  the way down to the label, and the *entry flags* of the statements it enters.

A GoTo may target a label in the same or an enclosing block, and (§10.7 recommendation) a label
inside an If, While, Do or Select body of such a block: the enclosing statements are entered
through an entry flag that skips their condition.  It may jump from a Catch back into its own Try
body (the retry idiom, §11.3).  Jumps into a For body (its limit and step were never evaluated) are
GPL3001; jumps into a Try/Catch/Finally or out of a Finally are GPL3002.  A jump out of a Try or
Catch block, which the manual calls illegal but the controller runs (the vendor's TCS does it,
docs/design/real-code.md), leaves the ``try`` through its ``finally``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from gpl2py import messages as M
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.gpl.semantics.check import child_blocks
from gpl2py.gpl.syntax import ast as A

_ENTERABLE = (A.If, A.While, A.DoLoop, A.Select)


@dataclass(eq=False)
class BlockInfo:
    block: A.Block
    parent: BlockInfo | None
    role: str  # body | try | catch | finally | loop | branch
    owner: A.Stmt | None  # the statement whose part this block is
    targets: list[A.Stmt] = field(default_factory=list)  # segment starts, in source order


@dataclass(eq=False)
class Jump:
    goto: A.GoTo
    restart: BlockInfo  # the dispatch loop the jump continues (its own block, or a Try body)
    states: list[tuple[BlockInfo, A.Stmt]]  # segment to select in each block, outermost first
    entries: list[A.Stmt]  # statements entered from outside (their entry flags are set)
    retry_try: A.Try | None = None  # set for a GoTo from a Catch into its Try


@dataclass
class GotoPlan:
    blocks: dict[A.Block, BlockInfo] = field(default_factory=dict)
    jumps: dict[A.GoTo, Jump] = field(default_factory=dict)
    retry_tries: set[A.Try] = field(default_factory=set)
    # statement entered from outside -> the block of it that the jump enters
    entered: dict[A.Stmt, A.Block] = field(default_factory=dict)
    # Try bodies whose only target is their first statement, reached by retry jumps only: each
    # attempt starts at the top, so the body needs no dispatch loop (the retry loop is enough)
    straight: set[A.Block] = field(default_factory=set)
    # loop bodies whose only targets are labels at their end, reached from inside the body: a jump
    # there ends the iteration, a ``continue`` of the loop (While, Do tested at the top or not at
    # all, For Each: loops whose Python form has no step after the body but a checkpoint)
    tails: set[A.Block] = field(default_factory=set)
    # labels at the end of the procedure's body, followed by nothing but labels and at most one
    # Return or Exit Sub/Function/Property -> that statement (None: the end of the procedure); a
    # jump there is that statement itself (``GoTo _exit`` is ``return``), so the body needs no
    # dispatch loop
    exits: dict[A.Label, A.Stmt | None] = field(default_factory=dict)
    exit_blocks: set[A.Block] = field(default_factory=set)

    def dispatch(self, block: A.Block) -> BlockInfo | None:
        info = self.blocks.get(block)
        if info is None or not info.targets or block in self.straight or block in self.tails \
                or block in self.exit_blocks:
            return None
        return info

    def segment(self, info: BlockInfo, stmt: A.Stmt) -> int:
        """Segment number of ``stmt`` in ``info``'s dispatch loop (segment 0 precedes the first)."""
        return info.targets.index(stmt) + 1


def plan_gotos(body: A.Block, sink: DiagnosticSink) -> GotoPlan:
    plan = GotoPlan()
    gotos: list[tuple[A.GoTo, BlockInfo]] = []
    label_at: dict[str, tuple[BlockInfo, A.Label]] = {}

    _walk_blocks(body, None, "body", None, plan, gotos, label_at)
    if not gotos:
        return plan
    wanted: dict[BlockInfo, set[A.Stmt]] = {}
    for g, where in gotos:
        found = label_at.get(g.label.lower())
        if found is None:
            continue  # reported by the semantic pass
        target, label = found
        up = _chain(where)
        down = _chain(target)
        common = next(b for b in up if b in down)
        crossed = up[: up.index(common)]
        retry: A.Try | None = None
        if any(c.role in ("try", "catch", "finally") for c in crossed):
            # the retry idiom: from a Catch into its own Try body
            retry = _retry(crossed, target)
            if retry is not None:
                plan.jumps[g] = Jump(g, target, [(target, label)], [], retry)
                plan.retry_tries.add(retry)
                wanted.setdefault(target, set()).add(label)
                continue
            if any(c.role == "finally" for c in crossed):
                sink.report(M.GOTO_ACROSS_TRY, g.span, name=g.label)
                continue
            # out of a Try or Catch block: the manual's "illegal" jump, which real code makes and
            # the controller runs (docs/design/real-code.md): Python leaves through the finally
        # enter the blocks between the common block and the label's block
        path = list(reversed(down[: down.index(common) + 1]))  # common ... target
        states: list[tuple[BlockInfo, A.Stmt]] = []
        entries: list[A.Stmt] = []
        ok = True
        for outer, inner in zip(path, path[1:]):
            stmt = inner.owner
            assert stmt is not None
            if not isinstance(stmt, _ENTERABLE):
                code = M.GOTO_ACROSS_TRY if isinstance(stmt, A.Try) else M.GOTO_INTO_BLOCK
                sink.report(code, g.span, name=g.label)
                ok = False
                break
            states.append((outer, stmt))
            entries.append(stmt)
            prev = plan.entered.get(stmt)
            if prev is not None and prev is not inner.block:
                sink.report(M.NOT_SUPPORTED, g.span, what="GoTo into two different branches of one statement")
                ok = False
                break
            plan.entered[stmt] = inner.block
        if not ok:
            continue
        states.append((target, label))
        for info, stmt in states:
            wanted.setdefault(info, set()).add(stmt)
        plan.jumps[g] = Jump(g, common, states, entries)
    for info, stmts in wanted.items():
        info.targets = [s for s in info.block.statements if s in stmts]
    for info in wanted:
        top = info.block.statements[0] if info.block.statements else None
        if info.targets == [top] and all(j.retry_try is not None for j in plan.jumps.values()
                                         if any(b is info for b, _ in j.states)):
            plan.straight.add(info.block)
        elif _ends_iteration(info, plan):
            plan.tails.add(info.block)
        elif _exit_tail(info, plan):
            plan.exit_blocks.add(info.block)
    return plan


def _walk_blocks(block: A.Block, parent: BlockInfo | None, role: str, owner: A.Stmt | None, plan: GotoPlan,
                 gotos: list[tuple[A.GoTo, BlockInfo]], label_at: dict[str, tuple[BlockInfo, A.Label]]) -> None:
    """Record ``block`` and the blocks nested in it in ``plan``, with every GoTo and the first
    Label of each name, in source order (a function, not a closure calling itself: no reference
    cycle left for the collector)."""
    info = BlockInfo(block, parent, role, owner)
    plan.blocks[block] = info
    for s in block.statements:
        if isinstance(s, A.Label):
            label_at.setdefault(s.name.lower(), (info, s))
        elif isinstance(s, A.GoTo):
            gotos.append((s, info))
        for child in child_blocks(s):
            if isinstance(s, A.Try):
                r = "try" if child is s.body else ("catch" if s.catch and child is s.catch.body else "finally")
            elif isinstance(s, (A.For, A.ForEach, A.While, A.DoLoop)):
                r = "loop"
            else:
                r = "branch"
            _walk_blocks(child, info, r, s, plan, gotos, label_at)


def _exit_tail(info: BlockInfo, plan: GotoPlan) -> bool:
    """Whether every target of ``info``, the procedure's body, is a label of its exit tail (the
    statements from the first target on are labels, then at most one Return or Exit of the
    procedure), reached by jumps that enter nothing on the way: each jump is then the tail's
    statement (recorded in ``plan.exits``)."""
    if info.parent is not None:
        return False
    stmts = info.block.statements
    first = next((k for k, s in enumerate(stmts) if s is info.targets[0]), -1)
    if first < 0:
        return False
    tail = stmts[first:]
    last = tail[-1]
    end: A.Stmt | None = None
    if isinstance(last, A.Return) or (isinstance(last, A.Exit) and last.kind in ("Sub", "Function", "Property")):
        end, tail = last, tail[:-1]
    if not all(isinstance(s, A.Label) for s in tail):
        return False
    if not all(j.retry_try is None and j.restart is info and len(j.states) == 1
               for j in plan.jumps.values() if any(b is info for b, _ in j.states)):
        return False
    for s in tail:
        plan.exits[s] = end  # type: ignore[index]
    return True


def _ends_iteration(info: BlockInfo, plan: GotoPlan) -> bool:
    """Whether ``info``'s targets are all labels at the end of a loop body that only jumps from
    within the body reach: a jump there is a ``continue`` of the loop."""
    owner = info.owner
    if info.role != "loop" or owner is None or owner in plan.entered:
        return False
    if not (isinstance(owner, (A.While, A.ForEach))
            or (isinstance(owner, A.DoLoop) and (owner.condition is None or owner.test_at_top))):
        return False
    stmts = info.block.statements
    first = stmts.index(info.targets[0]) if info.targets[0] in stmts else -1
    if first < 0 or not all(isinstance(s, A.Label) for s in stmts[first:]):
        return False
    return all(j.restart is info and j.retry_try is None for j in plan.jumps.values()
               if any(b is info for b, _ in j.states))


def _chain(b: BlockInfo | None) -> list[BlockInfo]:
    out: list[BlockInfo] = []
    while b is not None:
        out.append(b)
        b = b.parent
    return out


def _retry(crossed: list[BlockInfo], target: BlockInfo) -> A.Try | None:
    for c in crossed:
        if c.role == "catch":
            t = c.owner
            if isinstance(t, A.Try) and target.block is t.body and target.parent is c.parent:
                return t
            return None
        if c.role in ("try", "finally"):
            return None
    return None
