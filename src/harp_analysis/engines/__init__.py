"""The flight engines: each flies a launch (3DOF, 6DOF, MLT, the MKS and its variants, Appendix A's
numerics) and returns the shared trajectory table. Engines touch no data files, caches, plotting or
registries."""
