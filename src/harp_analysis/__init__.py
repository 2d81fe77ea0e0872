"""harp-analysis: a validated reproduction of Stutz (2013), the Modified Kepler Solution for
hypersonic projectiles launched into space, and its check against the HARP 16-inch gun data.

SI units throughout the package (m, s, kg, rad) unless a module's first line says otherwise.
"""

__version__ = "0.1.0"
