"""Data that ships with Torsal (a package only so that the wheel carries it)."""
