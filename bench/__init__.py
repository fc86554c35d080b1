"""Benchmarks: how fast the golden models and the RTL checks run (run by ``make bench``, not part of ``make test``)."""
