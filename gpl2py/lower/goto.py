"""Where GoTo jumps go: the block structure of a procedure, and which blocks need a dispatch loop.

Lowering keeps procedures structured; only a statement list that holds a label some GoTo targets
becomes a dispatch loop (docs/design/lowering.md, "GoTo").  This module computes, per procedure:

* the parent of every block and the *role* of each block (``body``, ``try``, ``catch``,
  ``finally``, ``loop``, ``branch``);
* for every targeted label, its block and its segment number in that block;
* for every GoTo whether it is legal (§10.7, §11.3): the label's block must enclose the GoTo without
  crossing a Try/Catch/Finally boundary, or the GoTo sits in a Catch and the label in the Try body
  of the same Try statement (the retry idiom).  Illegal jumps are reported (GPL3001/GPL3002).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from gpl2py import messages as M
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.semantics.check import child_blocks
from gpl2py.syntax import ast as A


@dataclass(eq=False)
class BlockInfo:
    block: A.Block
    parent: BlockInfo | None
    role: str  # body | try | catch | finally | loop | branch
    owner: A.Stmt | None  # the statement whose part this block is
    labels: list[str] = field(default_factory=list)  # targeted labels, in segment order (lower-case)


@dataclass(eq=False)
class Jump:
    goto: A.GoTo
    target: BlockInfo
    segment: int
    retry_try: A.Try | None = None  # set for a GoTo from a Catch into its Try


@dataclass
class GotoPlan:
    blocks: dict[A.Block, BlockInfo] = field(default_factory=dict)
    jumps: dict[A.GoTo, Jump] = field(default_factory=dict)
    retry_tries: set[A.Try] = field(default_factory=set)

    def dispatch(self, block: A.Block) -> BlockInfo | None:
        info = self.blocks.get(block)
        return info if info is not None and info.labels else None


def plan_gotos(body: A.Block, sink: DiagnosticSink) -> GotoPlan:
    plan = GotoPlan()
    gotos: list[tuple[A.GoTo, BlockInfo]] = []
    label_block: dict[str, BlockInfo] = {}

    def walk(block: A.Block, parent: BlockInfo | None, role: str, owner: A.Stmt | None) -> None:
        info = BlockInfo(block, parent, role, owner)
        plan.blocks[block] = info
        for s in block.statements:
            if isinstance(s, A.Label):
                label_block.setdefault(s.name.lower(), info)
            elif isinstance(s, A.GoTo):
                gotos.append((s, info))
            for child in child_blocks(s):
                if isinstance(s, A.Try):
                    r = "try" if child is s.body else ("catch" if s.catch and child is s.catch.body else "finally")
                elif isinstance(s, (A.For, A.ForEach, A.While, A.DoLoop)):
                    r = "loop"
                else:
                    r = "branch"
                walk(child, info, r, s)

    walk(body, None, "body", None)
    if not gotos:
        return plan
    for g, where in gotos:
        target = label_block.get(g.label.lower())
        if target is None:
            continue  # reported by the semantic pass
        chain: list[BlockInfo] = []
        b: BlockInfo | None = where
        while b is not None:
            chain.append(b)
            b = b.parent
        if target in chain:
            crossed = chain[: chain.index(target)]
            if any(c.role in ("try", "catch", "finally") for c in crossed):
                sink.report(M.GOTO_ACROSS_TRY, g.span, name=g.label)
                continue
            plan.jumps[g] = Jump(g, target, 0)
        else:
            # retry: the GoTo is in a Catch (not crossing another Try part) and the label is at the
            # top level of the same Try's body
            retry: A.Try | None = None
            for c in chain:
                if c.role == "catch":
                    t = c.owner
                    if isinstance(t, A.Try) and target.block is t.body:
                        retry = t
                    break
                if c.role in ("try", "finally"):
                    break
            if retry is None:
                inside_try = target.role in ("try", "catch", "finally") or any(
                    c.role in ("try", "catch", "finally") for c in chain)
                sink.report(M.GOTO_ACROSS_TRY if inside_try else M.GOTO_INTO_BLOCK, g.span, name=g.label)
                continue
            plan.jumps[g] = Jump(g, target, 0, retry)
            plan.retry_tries.add(retry)
        key = g.label.lower()
        if key not in target.labels:
            target.labels.append(key)
    # segment numbers follow source order of the labels within their block
    for info in plan.blocks.values():
        if info.labels:
            order = [s.name.lower() for s in info.block.statements if isinstance(s, A.Label)]
            info.labels = [name for name in order if name in info.labels]
            info.labels = list(dict.fromkeys(info.labels))
    for j in plan.jumps.values():
        j.segment = j.target.labels.index(j.goto.label.lower()) + 1
    return plan
