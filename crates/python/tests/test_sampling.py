"""strata.sampling: the generator against the published algorithms, the warps' pdfs against
their samples and against 1, their inverses, and the samplers' defining structure."""

import math
from statistics import NormalDist

import numpy as np
import pytest

from strata import sampling

# --- the generator, written out from the published algorithms ---------------------------------

MASK = 0xFFFFFFFF


def wang_hash(x):
    """Thomas Wang's 32-bit integer hash (his 2007 note)."""
    x = (x ^ 61) ^ (x >> 16)
    x = (x * 9) & MASK
    x ^= x >> 4
    x = (x * 0x27D4EB2D) & MASK
    return x ^ (x >> 15)


def xorshift32(state):
    """Marsaglia's xorshift32 with shifts 13, 17, 5 (Xorshift RNGs, 2003)."""
    state ^= (state << 13) & MASK
    state ^= state >> 17
    state ^= (state << 5) & MASK
    return state


def test_the_generator_is_xorshift32_seeded_by_the_wang_hash():
    for seed in [0, 1, 2, 12345, 0xFFFFFFFF]:
        rng = sampling.Rng(seed)
        state = wang_hash(seed) or 0x9E3779B9
        ours = rng.integers(100)
        for value in ours:
            state = xorshift32(state)
            assert value == state
        # Floats are the top 24 bits over 2^24.
        state = xorshift32(state)
        assert rng.next_f32() == (state >> 8) / 2**24
    assert sampling.wang_hash(12345) == wang_hash(12345)


def test_a_pixel_samples_stream_hashes_seed_pixel_and_index_in_turn():
    x, y, index, seed = 17, 4, 9, 3
    h = wang_hash(seed)
    h = wang_hash(h ^ x)
    h = wang_hash(((h + 0x68E31DA4) & MASK) ^ y)
    h = wang_hash(((h + 0xB5297A4D) & MASK) ^ index)
    assert sampling.Rng.for_sample(x, y, index, seed).next_u32() == xorshift32(wang_hash(h))
    # The independent sampler draws a pixel sample's numbers from that stream.
    points = sampling.points("independent", spp=10, seed=seed, pixel=(x, y), dimensions=3)
    rng = sampling.Rng.for_sample(x, y, index, seed)
    assert points[index].tolist() == rng.random(3).tolist()


def test_floats_are_in_the_unit_interval_and_next_below_in_range():
    rng = sampling.Rng(5)
    values = rng.random(100_000)
    assert values.dtype == np.float32 and values.min() >= 0.0 and values.max() < 1.0
    below = [rng.next_below(7) for _ in range(1000)]
    assert set(below) == set(range(7))
    with pytest.raises(ValueError):
        rng.next_below(0)


# --- the warps -------------------------------------------------------------------------------

def direction_grid(n_z, n_phi, z_low=-1.0, z_high=1.0):
    """Midpoints of an (n_z x n_phi) grid of cells equal in solid angle between z_low and
    z_high (z and phi uniform: d(omega) = dz d(phi)), and each cell's solid angle."""
    z = z_low + (np.arange(n_z) + 0.5) * (z_high - z_low) / n_z
    phi = (np.arange(n_phi) + 0.5) * 2 * np.pi / n_phi
    zz, pp = np.meshgrid(z, phi, indexing="ij")
    r = np.sqrt(np.maximum(0.0, 1 - zz**2))
    w = np.stack([r * np.cos(pp), r * np.sin(pp), zz], axis=-1).reshape(-1, 3)
    return w, (z_high - z_low) / n_z * 2 * np.pi / n_phi


DIRECTION_WARPS = {
    "uniform_hemisphere": sampling.uniform_hemisphere,
    "cosine_hemisphere": sampling.cosine_hemisphere,
    "uniform_sphere": sampling.uniform_sphere,
    "uniform_cone": sampling.uniform_cone(0.8),
}


@pytest.mark.parametrize("name", list(DIRECTION_WARPS))
def test_direction_pdfs_integrate_to_one_over_the_sphere(name):
    warp = DIRECTION_WARPS[name]
    # The cone's density jumps at z = 0.8: a grid line there keeps the midpoint rule exact.
    w, cell = direction_grid(2000, 64)
    total = float(np.sum(warp.pdf(w).astype(np.float64)) * cell)
    assert total == pytest.approx(1.0, abs=2e-3)


def test_the_disc_and_triangle_pdfs_integrate_to_one():
    n = 1000
    c = -1 + (np.arange(n) + 0.5) * 2 / n
    xx, yy = np.meshgrid(c, c, indexing="ij")
    disc = np.stack([xx, yy], axis=-1).reshape(-1, 2)
    total = float(np.sum(sampling.concentric_disk.pdf(disc).astype(np.float64)) * (2 / n) ** 2)
    assert total == pytest.approx(1.0, abs=5e-3)
    # Barycentric (b1, b2) on [0, 1]^2; the triangle of area A covers half of it, dA = 2A db.
    area = 3.0
    c = (np.arange(n) + 0.5) / n
    b1, b2 = np.meshgrid(c, c, indexing="ij")
    bary = np.stack([1 - b1 - b2, b1, b2], axis=-1).reshape(-1, 3)
    pdf = sampling.uniform_triangle(area).pdf(bary).astype(np.float64)
    assert float(np.sum(pdf) * 2 * area / n**2) == pytest.approx(1.0, abs=5e-3)


def uniform_points(n, seed):
    return sampling.Rng(seed).random(2 * n).reshape(n, 2)


ALL_WARPS = {**DIRECTION_WARPS, "concentric_disk": sampling.concentric_disk,
             "uniform_triangle": sampling.uniform_triangle(0.5)}


@pytest.mark.parametrize("name", list(ALL_WARPS))
def test_inverse_round_trips(name):
    warp = ALL_WARPS[name]
    # Away from the edges, where azimuths wrap and the disc's map has its seams.
    u = 0.001 + 0.998 * uniform_points(20_000, seed=11)
    points = warp.sample(u)
    back = warp.invert(points)
    assert np.max(np.abs(back - u)) < 2e-4
    again = warp.sample(back)
    assert np.max(np.abs(again - points)) < 2e-4
    assert np.all(warp.pdf(points) > 0)


# Chi-square goodness of fit of each direction warp's samples to its own pdf, in 8 bands of z by
# 8 sectors of phi over the warp's support. Significance level 1e-3 per warp, so 4e-3 for the
# four (Bonferroni). The expected counts come from the pdf by the midpoint rule on a 64x64
# sub-grid of each cell; with 200,000 samples every cell expects far more than 5.
ALPHA_PER_WARP = 1e-3
SAMPLES = 200_000
SUPPORT = {"uniform_hemisphere": (0.0, 1.0), "cosine_hemisphere": (0.0, 1.0),
           "uniform_sphere": (-1.0, 1.0), "uniform_cone": (0.8, 1.0)}


def chi_square(warp, z_range, samples):
    """The statistic and its critical value for `samples` (unit directions) against `warp.pdf`."""
    n_z, n_phi, sub = 8, 8, 64
    z_low, z_high = z_range
    w, cell = direction_grid(n_z * sub, n_phi * sub, z_low, z_high)
    density = warp.pdf(w).astype(np.float64).reshape(n_z, sub, n_phi, sub)
    expected = density.sum(axis=(1, 3)) * cell * len(samples)
    z_bin = np.clip(((samples[:, 2] - z_low) / (z_high - z_low) * n_z).astype(int), 0, n_z - 1)
    phi = np.mod(np.arctan2(samples[:, 1], samples[:, 0]), 2 * np.pi)
    phi_bin = np.clip((phi / (2 * np.pi) * n_phi).astype(int), 0, n_phi - 1)
    observed = np.zeros((n_z, n_phi))
    np.add.at(observed, (z_bin, phi_bin), 1)
    assert expected.min() > 5
    statistic = float(np.sum((observed - expected) ** 2 / expected))
    dof = n_z * n_phi - 1
    # Wilson and Hilferty's approximation of the chi-square quantile.
    z = NormalDist().inv_cdf(1 - ALPHA_PER_WARP)
    critical = dof * (1 - 2 / (9 * dof) + z * math.sqrt(2 / (9 * dof))) ** 3
    return statistic, critical


@pytest.mark.parametrize("name", list(DIRECTION_WARPS))
def test_samples_follow_their_pdf(name):
    warp = DIRECTION_WARPS[name]
    samples = warp.sample(uniform_points(SAMPLES, seed=21)).astype(np.float64)
    statistic, critical = chi_square(warp, SUPPORT[name], samples)
    assert statistic < critical, (statistic, critical)


def test_the_fit_test_rejects_samples_of_another_density():
    # Power: uniform hemisphere samples judged against the cosine pdf must fail.
    samples = sampling.uniform_hemisphere.sample(uniform_points(SAMPLES, seed=21))
    statistic, critical = chi_square(sampling.cosine_hemisphere, (0.0, 1.0),
                                     samples.astype(np.float64))
    assert statistic > critical


def test_bad_warp_inputs_are_value_errors():
    with pytest.raises(ValueError, match=r"\(n, 2\)"):
        sampling.cosine_hemisphere.sample(np.zeros((4, 3)))
    with pytest.raises(ValueError, match="cos_theta_max"):
        sampling.uniform_cone(1.0).sample(np.zeros((1, 2)))
    with pytest.raises(ValueError, match="area"):
        sampling.uniform_triangle(0.0).pdf(np.zeros((1, 3)))


# --- the samplers ----------------------------------------------------------------------------

def test_every_sampler_gives_unit_interval_points_that_depend_on_seed_and_pixel():
    for kind in sampling.SAMPLERS:
        points = sampling.points(kind, spp=32, seed=1, pixel=(3, 5), dimensions=5)
        assert points.shape == (32, 5) and points.dtype == np.float32
        assert points.min() >= 0 and points.max() < 1
        assert np.array_equal(points, sampling.points(kind, 32, seed=1, pixel=(3, 5),
                                                      dimensions=5))
        assert not np.array_equal(points, sampling.points(kind, 32, seed=2, pixel=(3, 5),
                                                          dimensions=5))
        assert not np.array_equal(points, sampling.points(kind, 32, seed=1, pixel=(4, 5),
                                                          dimensions=5))
    with pytest.raises(ValueError, match="no sampler called"):
        sampling.points("halton", 4)


def test_stratified_points_put_one_sample_in_each_stratum():
    for pixel in [(0, 0), (7, 9)]:
        points = sampling.points("stratified", spp=16, seed=4, pixel=pixel, dimensions=4)
        for d in (0, 2):
            cells = {(int(x * 4), int(y * 4)) for x, y in points[:, d:d + 2]}
            assert len(cells) == 16


def test_sobol_points_are_a_0_2_net():
    # Every elementary interval of area 1/16 (1x16, 2x8, 4x4, 8x2, 16x1 boxes) holds one point.
    points = sampling.points("sobol", spp=16, seed=6, pixel=(2, 1), dimensions=2)
    for k in range(5):
        nx, ny = 2**k, 2 ** (4 - k)
        cells = {(int(x * nx), int(y * ny)) for x, y in points}
        assert len(cells) == 16, (nx, ny)
    # Independent points are not a net (the check can fail).
    independent = sampling.points("independent", spp=16, seed=6, dimensions=2)
    assert len({(int(x * 4), int(y * 4)) for x, y in independent}) < 16
