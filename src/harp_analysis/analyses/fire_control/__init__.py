"""Fire control (Chapter 7 A, built): firing solutions (:mod:`.firing`, by the compiled
:mod:`.solver`, or moved onto the calibrated MKS by :mod:`.calibrated`), their 3DOF check
(:mod:`.verification`), intercepts and raids (:mod:`.intercepts`) and miss maps
(:mod:`.envelope`). The studies of the method (the text's counts and timings, first guesses,
the models compared) are :mod:`.studies`'s. The names a user starts from are here; the
package's own modules import from the submodules."""

from .firing import BARBADOS_HP, TargetPoint, barbados_case, destination, firing_solutions
from .intercepts import intercept, intercept_window, raid, raid_roots, raid_windows
from .verification import verify_with_3dof

__all__ = [
    "firing_solutions",
    "verify_with_3dof",
    "raid_windows",
    "raid_roots",
    "raid",
    "barbados_case",
    "BARBADOS_HP",
    "destination",
    "TargetPoint",
    "intercept",
    "intercept_window",
]
