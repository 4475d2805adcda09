"""One claim of a paper, set beside our numbers: the type every paper's module returns its claims as
(thesis_tables.claims, lrsm_tables.claims, ldm_claims.claims, temporal_tables.claims), passed in
memory to claims.py, which writes them once, a row of RESULTS_DIR/claims.csv each.

A Claim holds what claims.csv says of it: the paper, the table its evidence lies in (`source`), the
claim's text, its kind, the paper's value and ours, the renderer and cores ours ran on, the verdict
and its reason. A claim tested at several settings is one Claim (claims.counted_once): the Claims
at each setting lie beneath it in `settings`, the evidence of its verdict.

Verdicts: `reproduced`, `not reproduced`, or `not measurable here` (no run of ours answers it, or
it is an absolute time on the paper's GPU).
Kinds, by what a claim depends on:
- `machine_independent`: memory, error, leaks: any machine judges them;
- `time_order`: an order or a ratio of times: it carries over between machines only as far as the
  renderer's pipeline resembles the paper's GPU, so it is judged on the renderer the claim names;
- `absolute_time`: a paper's absolute time on its GPU: `not measurable here` on another renderer
  (a time on llvmpipe says nothing about a GTX 770's).
Tolerances, one per kind of claim (the choice this package makes, stated once):
- memory holds within MEMORY_TOLERANCE (25%) of the paper's figure, every paper alike (byte counts
  do not depend on the renderer; a paper's figure may count what ours does not, or round); whether
  our bytes equal the paper's own formula is a separate fact, stated in the reason, never the
  verdict. A run refused for memory is measured by its plan (what the ledger recorded before it
  would have allocated), the same bytes;
- errors are compared as intervals (uncertainty.error_interval): overlapping intervals are a tie,
  no tolerance, and a tie is no win;
- orders of times at the machine's time resolution (uncertainty.compare_times: closer than it is a
  tie);
- qualitative claims by the threshold the module judging them states (a leak visible from 1% of
  display white, lrsm_tables.LEAK_VISIBLE; temporal_tables' flicker and frozen scale).
"""
import re
from dataclasses import dataclass, field, fields

REPRODUCED, NOT_REPRODUCED, NOT_MEASURABLE = "reproduced", "not reproduced", "not measurable here"
VERDICTS = (REPRODUCED, NOT_REPRODUCED, NOT_MEASURABLE)
MACHINE_INDEPENDENT, TIME_ORDER, ABSOLUTE_TIME = "machine_independent", "time_order", "absolute_time"
KINDS = (MACHINE_INDEPENDENT, TIME_ORDER, ABSOLUTE_TIME)
MEMORY_TOLERANCE = 0.25  # a memory figure agrees within 25% of the paper's

THESIS = "Le 2014 (thesis): interactive caustics and multi-resolution indirect illumination"
LRSM = "Sugihara et al. 2014: Layered Reflective Shadow Maps (LRSM)"
LDM = "Layered depth maps (LDM) for ambient occlusion and indirect light"


@dataclass
class Claim:
    """A claim and its verdict; `settings`: the Claims at each setting it was tested at, where it
    stands for several (empty otherwise)."""
    paper: str
    source: str
    claim: str
    kind: str = MACHINE_INDEPENDENT
    paper_value: str = ""
    our_value: str = ""
    renderer: str = ""
    cores: str = ""
    verdict: str = NOT_MEASURABLE
    reason: str = ""
    settings: list = field(default_factory=list)

    def __post_init__(self):
        if self.verdict not in VERDICTS:
            raise ValueError(f"claim {self.claim!r}: verdict {self.verdict!r} is none of {VERDICTS}")
        if self.kind not in KINDS:
            raise ValueError(f"claim {self.claim!r}: kind {self.kind!r} is none of {KINDS}")

    def row(self):
        """The claim as a row of claims.csv."""
        return {c: getattr(self, c) for c in COLUMNS}


# claims.csv's columns: a Claim's fields but the settings beneath it.
COLUMNS = [f.name for f in fields(Claim) if f.name != "settings"]


def verdict(holds):
    """The verdict of a claim judged True (holds) or False; None: not measurable here."""
    return NOT_MEASURABLE if holds is None else REPRODUCED if holds else NOT_REPRODUCED


def paper_number(text):
    """A paper's figure as a number: '156.4', or 'about 3000 (3 GB)' read as 3000."""
    m = re.search(r"[-+]?\d+(?:\.\d+)?", text)
    return float(m.group(0)) if m else float("nan")


def memory_verdict(ours_mb, paper_mb):
    """(verdict, reason) of a memory claim under the one tolerance for memory."""
    ratio = ours_mb / paper_mb
    v = REPRODUCED if abs(ratio - 1) <= MEMORY_TOLERANCE else NOT_REPRODUCED
    return v, f"ours {ours_mb:g} MB = {ratio:.3f}x the paper's (tolerance {100 * MEMORY_TOLERANCE:.0f}%)"
