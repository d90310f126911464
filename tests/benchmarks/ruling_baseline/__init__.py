"""A frozen copy of the RulingDevelopable solver as it was before issue 10 (commit d980062):
the sampled partner search, kept only as the benchmark's baseline for today's time.
Never imported by the app or the tests."""
