"""The claims ledger's computations that belong to no analysis of their own."""
