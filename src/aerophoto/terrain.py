"""Demo terrains of the virtual world: smooth analytic hills and the site with adjustable relief.

Layer 3 (the virtual world).  Each class implements :class:`aerophoto.geometry.Terrain`
(``height(X, Y)``, ``z_min_m``, ``z_max_m``), so it can be passed wherever a terrain is
expected (:func:`aerophoto.geometry.photo_to_dem`, :func:`aerophoto.geometry.as_terrain`).
"""

from __future__ import annotations

__all__: list[str] = []
