"""The foundation: numerics (compiled kernels), the Earth's constants, input checks, caches, paths
and the one sweep. Imports nothing else of the package."""
