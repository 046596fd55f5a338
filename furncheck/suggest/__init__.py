"""Suggestions that make an invalid design valid (paper sections 6.4 and 6.5)."""

from furncheck.suggest.continuous import Suggestion, SuggestionReport, suggest_design

__all__ = ["Suggestion", "SuggestionReport", "suggest_design"]
