"""Widget hints: how a front-end lets a designer set a node by hand, declared by the node.

A node type names one :class:`Widget` in its ``widget`` class attribute and keeps the
widget's state in its settings, under the names below. A front-end chooses its widget
from the hint alone — never from the node's type id — so a plug-in node that declares
``widget = Widget.SLIDER`` and these settings gets a slider in the app.

- ``SLIDER``: settings ``value``, ``min``, ``max`` (and ``decimals`` for a number
  slider); the slider gives whole numbers when the node's first output is an Integer.
- ``TOGGLE``: setting ``value``, True or False.
- ``VALUE_LIST``: settings ``items`` (a list, each ``{"name": ..., "value": ...}``) and
  ``selected`` (the chosen item's position).
- ``PANEL``: a note: setting ``text``, shown when nothing is wired; otherwise the
  node's first output is shown. Its ports carry no labels and it can be resized.
- ``EXPRESSION``: settings ``expression`` (the formula) and ``variables`` (one input
  each); a front-end offers to edit the formula.
"""

from __future__ import annotations

import enum


class Widget(enum.Enum):
    """The kinds of widget a node may ask for."""

    SLIDER = "slider"
    TOGGLE = "toggle"
    VALUE_LIST = "value list"
    PANEL = "panel"
    EXPRESSION = "expression"
