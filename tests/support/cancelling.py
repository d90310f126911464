"""A node whose cancel token is pressed at its N-th look, for the tests that a long node
looks at the token inside its kernel and stops there."""

from __future__ import annotations

from torsal.engine.node import Node


def cancel_at_look(node: Node, look: int) -> list[int]:
    """Make ``node``'s token cancel at its ``look``-th check (``check_cancelled``, which the
    kernels' watch checks call); returns the list of looks made, which grows as it runs."""
    looks: list[int] = []

    def check() -> None:
        looks.append(1)
        if len(looks) == look:
            node.token.cancel()
        node.token.check()

    node.check_cancelled = check
    return looks
