"""The ``waves`` palette: an example Torsal plug-in (see docs/plugins.md of Torsal).

Torsal reads these three declarations and nothing else from this file: the palette's
name (the part of each type id before the dot), the modules holding its node types and
the modules defining its value types.
"""

PALETTE = "waves"
NODE_TYPES = ("nodes",)
VALUE_TYPES = ("profile",)
