"""Studies of the fire-control method, not the method: the text's counts and timings of a
firing solution against the 3DOF's (:mod:`.costs`), the improved MKS as the solver's first
guess (:mod:`.first_guess`), and both models' roots judged by the 3DOF (:mod:`.model_comparison`).
They import the method (:mod:`..firing`, :mod:`..verification`, :mod:`..intercepts`,
:mod:`..envelope`); the method imports none of them."""
