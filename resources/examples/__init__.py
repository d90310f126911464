"""The example graphs (``*.graph``): found through :mod:`app.examples`, written by
tools/build_examples.py."""
