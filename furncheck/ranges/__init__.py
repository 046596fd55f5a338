"""Valid ranges of design DOFs (paper section 6.3).

For one DOF, the others held (its neighbours adjusted by the geometric constraints of
``dofs``), the valid range is the interval of values around the current one for which the
design stays valid: every joint durable, stable in every load case, the same joints and
ground contacts.  Each side is searched in two stages:

* how far the geometry reaches (the same joints and contacts, ``check_edit``): the margins
  of its criteria (``geometry.EditMargins``; linear in the step for translations and size
  changes) predict the first one to flip, and two geometry checks confirm it, one half a
  resolution before (valid) and one half after (not); a rotation's prediction is refined
  on its margins first; a wrong prediction falls back to bisection;
* if the design is not valid at that reach, the physical limit inside it: a bracket of
  one valid and one invalid value is closed to ``RANGE_RESOLUTION``, every probe a full
  check of the edited design.  The probes go where validity is likely to change: just
  past the step where a loaded joint loses a nail (found from the joint's length, without
  statics), else at the force sensitivity's prediction (eq. 6) of where the first joint
  reaches its nail capacity or the first contact lets go, else at the zero of the
  design's margin interpolated through the probes; bisection where these do not halve
  the bracket.

The reported end is the last value found valid (by a full check); a value at most one
resolution step beyond it was found invalid (or the end is the search limit).

Each side's search is a generator: it yields the evaluations it needs (``_Kept``: an edit
and its geometry check; ``_Margins``: geometric margins of an edit; ``_Statics``: a full
check) and receives their results.  ``Evaluator._run`` advances the searches of all
DOFs together, and every round answers the evaluations they wait for as one batch: the
geometry checks and the margins of all of them in one vectorized pass each
(``edit_check.check_edit_many``, ``geometry.edit_margins_many``).  No search depends on
another's results, so the ranges are the same however the DOFs are batched.

The package, by job:

    finder     RangeFinder: the searches of each side of a DOF, its physical limit,
               DofRange, dof_ranges
    notes      what a row says besides its interval: a beam the edit turns, a size's
               floor, a value pinned
    reach      ReachSearch: how far the geometry lets a DOF go; doubling and bisection
    shares     the DOFs shared among worker processes (--jobs) or a Dask cluster
    batches    Evaluator: a design's edits and their checks, answered in batches for
               searches advanced together
    estimates  where validity is likely to change: the margin's zero, a joint losing a
               nail, the first flip of modelled geometric margins, the sensitivity's
               margins
"""

from furncheck.ranges.finder import (
    RANGE_RESOLUTION,
    SEARCH_LIMIT,
    DofRange,
    RangeFinder,
    dof_ranges,
)

__all__ = ["RANGE_RESOLUTION", "SEARCH_LIMIT", "DofRange", "RangeFinder", "dof_ranges"]
