"""The example graphs (``*.graph``): found through :mod:`torsal.app.examples`, written by
tools/build_examples.py."""
