"""The HARP 16-inch guns (Chapter 6): Appendices D and E, the apogee models, round trajectories,
statistics and what the appendices identify."""
