"""The flight engines: each flies a launch (3DOF, 6DOF, MLT, the MKS and its variants, Appendix A's
numerics) and returns the shared trajectory table; :mod:`.catalogue` holds a record of each, what
it models, and ``fly(launch, engine=...)``. Engines touch no data files, caches, plotting, or the
figure registry and claims ledger of reporting."""
