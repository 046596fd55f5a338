"""Suggestions that make an invalid design valid (paper sections 6.4 and 6.5).

    margins, candidates, continuous, edits   continuous suggestions (Algorithm 1)
    discrete                                 an added support plank
    closures                                 a near miss closed along each direction
                                             tried, with thicker boards
    ranking                                  ``suggest_design``: both, ranked and validated
"""

from furncheck.suggest.ranking import suggest_design
from furncheck.suggest.suggestion import Suggestion, SuggestionReport

__all__ = ["Suggestion", "SuggestionReport", "suggest_design"]
