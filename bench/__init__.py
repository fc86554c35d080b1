"""Benchmarks of issue 6 (run by ``make bench``, not part of ``make test``)."""
