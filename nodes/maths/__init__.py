"""Maths: expressions, number sequences, domains and random numbers."""
