"""Studies of the fire-control method, not the method: the text's counts and timings of a
firing solution against the 3DOF's (:mod:`.costs`), the improved MKS as the solver's first
guess (:mod:`~harp_analysis.analyses.fire_control.studies.first_guess`), and both models' roots
judged by the 3DOF (:mod:`.model_comparison`). They import the method
(:mod:`~harp_analysis.analyses.fire_control.firing`,
:mod:`~harp_analysis.analyses.fire_control.verification`,
:mod:`~harp_analysis.analyses.fire_control.studies.costs.RaidComparison.intercepts`,
:mod:`~harp_analysis.analyses.fire_control.envelope`); the method imports none of them."""
