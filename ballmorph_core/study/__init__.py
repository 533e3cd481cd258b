"""The paper's study (section 6): six quality measures of a morph. The add-on does not need it."""

from .measures import MEASURES, measure

__all__ = ["MEASURES", "measure"]
