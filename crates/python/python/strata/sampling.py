"""Strata's sampling routines over NumPy arrays, for redoing the lecture's experiments.

    from strata import sampling
    rng = sampling.Rng(7)
    u = rng.random(2000).reshape(-1, 2)              # uniform points of [0, 1)^2
    w = sampling.cosine_hemisphere.sample(u)         # (1000, 3) unit directions, z >= 0
    pdf = sampling.cosine_hemisphere.pdf(w)          # cos(theta) / pi per steradian
    u_again = sampling.cosine_hemisphere.invert(w)   # == u up to float32 rounding
    pts = sampling.points("sobol", spp=64, seed=1)   # a pixel's 64 samples, 2 dimensions

All arrays are float32. These are the renderer's own functions (the `sampling` crate), not
copies: the numbers are those a render draws.
"""

import numpy as _np

from ._strata import SAMPLERS as _SAMPLERS
from ._strata import Rng, wang_hash
from ._strata import sampler_points as _sampler_points
from ._strata import warp_invert as _warp_invert
from ._strata import warp_pdf as _warp_pdf
from ._strata import warp_sample as _warp_sample

__all__ = [
    "Rng",
    "SAMPLERS",
    "Warp",
    "concentric_disk",
    "cosine_hemisphere",
    "points",
    "uniform_cone",
    "uniform_hemisphere",
    "uniform_sphere",
    "uniform_triangle",
    "wang_hash",
]

#: The samplers' names, as `strata render --sampler` takes them (the renderer's own list).
SAMPLERS = tuple(_SAMPLERS)


def _rows(x, columns, name):
    """`x` as a C-contiguous float32 array of shape (n, columns); one row may be given alone."""
    array = _np.ascontiguousarray(x, dtype=_np.float32)
    if array.ndim == 1:
        array = array.reshape(1, -1)
    if array.ndim != 2 or array.shape[1] != columns:
        raise ValueError(f"{name} has shape {_np.shape(x)}; expected (n, {columns})")
    return array


class Warp:
    """A map from the unit square to a domain, with its density and its inverse.

    - `sample(u)`: the points that the rows of `u` (shape (n, 2), in [0, 1)^2) map to: shape
      (n, 3) for directions and barycentric coordinates, (n, 2) for the disc;
    - `pdf(points)`: the density of `sample`'s points at `points` in the domain's measure (per
      steradian for directions, per unit area for the disc and the triangle), zero outside the
      domain;
    - `invert(points)`: the `u` that `sample` maps to `points`.
    """

    def __init__(self, name, dimension, parameter=0.0):
        self.name = name
        self.dimension = dimension
        self.parameter = float(parameter)

    def sample(self, u):
        return _warp_sample(self.name, _rows(u, 2, "u"), self.parameter)

    def pdf(self, points):
        return _warp_pdf(self.name, _rows(points, self.dimension, "points"), self.parameter)

    def invert(self, points):
        return _warp_invert(self.name, _rows(points, self.dimension, "points"), self.parameter)

    def __repr__(self):
        return f"strata.sampling.Warp({self.name!r}, parameter={self.parameter})"


#: Directions uniform over the upper (z >= 0) hemisphere: pdf 1 / (2 pi).
uniform_hemisphere = Warp("uniform_hemisphere", 3)
#: Directions over the upper hemisphere with density cos(theta) / pi (disc projection).
cosine_hemisphere = Warp("cosine_hemisphere", 3)
#: Directions uniform over the unit sphere: pdf 1 / (4 pi).
uniform_sphere = Warp("uniform_sphere", 3)
#: Points uniform on the unit disc by Shirley and Chiu's concentric map: pdf 1 / pi.
concentric_disk = Warp("concentric_disk", 2)


def uniform_cone(cos_theta_max):
    """Directions uniform within the cone theta <= theta_max around +z: pdf
    1 / (2 pi (1 - cos theta_max))."""
    return Warp("uniform_cone", 3, cos_theta_max)


def uniform_triangle(area=1.0):
    """Barycentric coordinates of points uniform by area on a triangle of `area`: pdf 1 / area."""
    return Warp("uniform_triangle", 3, area)


def points(sampler, spp, seed=0, pixel=(0, 0), dimensions=2):
    """The first `dimensions` numbers of each of the `spp` samples of `pixel` that `sampler`
    (one of `SAMPLERS`, laid out for `spp` samples) draws with `seed`, as an array of shape
    (spp, dimensions). Numbers come in pairs (one 2D dimension each, as the renderer draws film
    positions and directions), the last alone when `dimensions` is odd."""
    x, y = pixel
    return _sampler_points(sampler, int(spp), int(seed), int(x), int(y), int(dimensions))
