"""The two 16-inch HARP gun sites of Stutz (2013), Chapter 6: Barbados and Yuma, in SI units."""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..foundation.validation import Bounds, check_choice, finite_array
from .atmosphere import SEA_LEVEL_DENSITY_KG_M3

__all__ = ["LaunchSite", "BARBADOS", "YUMA", "dms_to_deg", "get_site"]


@dataclass(frozen=True)
class LaunchSite:
    """A gun site: latitude, gun bearing from true north, surface air density, gun elevation."""

    name: str
    latitude_rad: float
    gun_bearing_rad: float
    surface_density_kg_m3: float
    elevation_rad: float
    source: str

    @property
    def key(self) -> str:
        """The lower-case name that keys the site's files and tables ("barbados", "yuma")."""
        return self.name.lower()


def dms_to_deg(degrees: float, minutes: float, seconds: float) -> float:
    """Degrees, minutes, seconds to decimal degrees; the sign of ``degrees`` applies to all."""
    degrees = float(finite_array(degrees, "degrees"))
    for value, name in ((minutes, "minutes"), (seconds, "seconds")):
        Bounds(low=0, high=60, high_inclusive=False).finite(value, name)
    return math.copysign(abs(degrees) + minutes / 60 + seconds / 3600, degrees)


BARBADOS = LaunchSite(
    name="Barbados",
    # 13.077222 deg; the text rounds it to 13.0772 deg in eq. (6.16).
    latitude_rad=math.radians(dms_to_deg(13, 4, 38)),
    gun_bearing_rad=math.radians(109.0),
    surface_density_kg_m3=SEA_LEVEL_DENSITY_KG_M3,
    elevation_rad=math.radians(85.0),
    source=(
        "Stutz (2013): latitude 13°4'38\" N, Ch. 6 C before eq. (6.16); bearing 109° true, "
        "Ch. 6 B (Fig. 6.4) and Ch. 6 C; density 1.225 kg/m^3 (US Standard Atmosphere), Ch. 6 C; "
        "elevation 85°, Ch. 6 B."
    ),
)

YUMA = LaunchSite(
    name="Yuma",
    latitude_rad=math.radians(dms_to_deg(32, 52, 33)),
    gun_bearing_rad=math.radians(78.0),
    surface_density_kg_m3=1.14,
    elevation_rad=math.radians(85.0),
    source=(
        "Stutz (2013): latitude 32°52'33\" N, bearing 078° true and density 1.14 kg/m^3, Ch. 6 D; "
        "elevation 85°, Ch. 6 B."
    ),
)

_SITES = {site.name.lower(): site for site in (BARBADOS, YUMA)}


def get_site(site: str | LaunchSite) -> LaunchSite:
    """The site ``site`` names ("barbados" or "yuma", any case), or ``site`` itself if it is a
    :class:`LaunchSite`: public functions resolve a name once here and pass the site on.

    Parameters
    ----------
    site : str or LaunchSite
        ``"barbados"`` or ``"yuma"``, any case, or a site.

    Returns
    -------
    LaunchSite
        The gun site: its latitude, elevation, gun bearing and surface air density.
    """
    if isinstance(site, LaunchSite):
        return site
    key = site.lower() if isinstance(site, str) else site
    return _SITES[check_choice(key, "site", _SITES)]
