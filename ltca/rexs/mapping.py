"""The record of a mapping from REXS to a case: which attributes it read, and those it could not hold (with why)."""
from __future__ import annotations

from dataclasses import dataclass

from .model import Component

__all__ = ["Unmapped", "Used"]


@dataclass(frozen=True)
class Unmapped:
    """An attribute of the model the case cannot represent, and why."""
    component: int
    component_type: str
    attribute: str
    value: object
    unit: str | None
    reason: str


class Used:
    """The attributes a mapping consumed, by component id."""

    def __init__(self):
        self.ids: dict[int, set[str]] = {}
        self.reasons: dict[tuple[int, str], str] = {}

    def take(self, c: Component, *attrs: str) -> None:
        self.ids.setdefault(c.id, set()).update(attrs)

    def skip(self, c: Component, attr: str, reason: str) -> None:
        self.reasons[(c.id, attr)] = reason
