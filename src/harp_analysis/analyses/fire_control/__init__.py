"""Fire control (Chapter 7 A, built): firing solutions, the compiled solver, intercepts and raids,
envelopes and first guesses."""
