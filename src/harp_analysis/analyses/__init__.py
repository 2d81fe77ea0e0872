"""The analyses built on the engines: the dissertation's comparisons and cases, the rotating Earth,
the error budget, the improved MKS's calibration; the HARP guns, fire control and the ledger's
computations in wings of their own."""
