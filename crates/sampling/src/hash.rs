//! Integer hashing for samplers: key derivation and random-looking permutations of [0, n)
//! that need no storage, so any (pixel, sample, dimension) can be evaluated on its own.

/// MurmurHash3's 32-bit finaliser: a bijection of `u32` in which every input bit affects every output bit.
#[inline]
pub(crate) fn mix32(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x85EB_CA6B);
    x ^= x >> 13;
    x = x.wrapping_mul(0xC2B2_AE35);
    x ^ (x >> 16)
}

/// A 64-bit bijection in which every input bit affects every output bit: the SplitMix64 output
/// function (Stafford's "Mix13" finaliser). Consecutive inputs spaced by an odd constant give
/// unrelated outputs, which makes a cheap counter-based stream of 64-bit hashes.
#[inline]
pub(crate) fn mix64(mut x: u64) -> u64 {
    x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    x ^ (x >> 31)
}

/// A hash of the ordered pair (a, b); swapping the arguments gives an unrelated value.
#[inline]
pub(crate) fn hash2(a: u32, b: u32) -> u32 {
    mix32(a ^ mix32(b.wrapping_add(0x9E37_79B9)))
}

/// Rounds of the Feistel network in [`permute`]; each costs one [`mix32`]. Two rounds fail the
/// key-dependence test below, three pass every test; four leave a margin.
const FEISTEL_ROUNDS: u32 = 4;

/// Where `index` lands under the permutation of [0, `len`) selected by `key`.
///
/// Each `key` gives a different bijection of [0, `len`) that costs O(1) on average and needs no table:
/// 1. an unbalanced Feistel network on the bits of the smallest power-of-two range holding `len`
///    values (each round xors one part with a keyed [`mix32`] of the other, then swaps them), applied
///    repeatedly until the value falls below `len` ("cycle walking"; fewer than two passes on average),
///    which restricts it to a bijection of [0, `len`);
/// 2. a keyed rotation by c ∈ [0, `len`), which makes every `index` land on every value with the same
///    probability 1 / `len` over random keys, whatever the structure of step 1.
///
/// `index` must be below `len`; `len` 0 or 1 gives 0.
#[inline]
pub(crate) fn permute(index: u32, len: u32, key: u32) -> u32 {
    debug_assert!(
        index < len.max(1),
        "permute: index {index} outside [0, {len})"
    );
    if len <= 1 {
        return 0;
    }
    let bits = 32 - (len - 1).leading_zeros();
    let mask = u32::MAX >> (32 - bits);
    let round_key = mix32(key);
    let mut i = index;
    loop {
        for round in 0..FEISTEL_ROUNDS {
            // Alternate which part is the (unchanged, then swapped up) right half.
            let right_bits = if round % 2 == 0 {
                bits / 2
            } else {
                bits - bits / 2
            };
            let left_bits = bits - right_bits;
            let right = i & ((1 << right_bits) - 1);
            let left = i >> right_bits;
            let f = mix32(right ^ round_key.wrapping_add(round.wrapping_mul(0x9E37_79B9)));
            let left_mask = (1_u32 << left_bits) - 1;
            i = ((right << left_bits) | ((left ^ f) & left_mask)) & mask;
        }
        if i < len {
            break;
        }
    }
    let rotation = ((u64::from(mix32(key ^ 0x68E3_1DA4)) * u64::from(len)) >> 32) as u32;
    let rotated = i + rotation;
    if rotated >= len {
        rotated - len
    } else {
        rotated
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn permute_is_a_bijection_for_every_length() {
        for len in 1..=300_u32 {
            for key in [0, 1, 7, 0xDEAD_BEEF, u32::MAX] {
                let mut seen = vec![false; len as usize];
                for i in 0..len {
                    let p = permute(i, len, key);
                    assert!(p < len, "len {len} key {key}: {i} -> {p}");
                    assert!(!seen[p as usize], "len {len} key {key}: {p} hit twice");
                    seen[p as usize] = true;
                }
            }
        }
    }

    #[test]
    fn permute_depends_on_the_key() {
        // Over many keys, where 0 and 1 land must cover all ordered pairs of distinct values
        // about equally often: a weak key schedule leaves some pairs rare or unreachable.
        let len = 8_u32;
        let mut counts = vec![0_u32; (len * len) as usize];
        let keys = 56_000_u32;
        for key in 0..keys {
            let a = permute(0, len, key);
            let b = permute(1, len, key);
            counts[(a * len + b) as usize] += 1;
        }
        let expected = f64::from(keys) / f64::from(len * (len - 1));
        for a in 0..len {
            for b in 0..len {
                let c = f64::from(counts[(a * len + b) as usize]);
                if a == b {
                    assert_eq!(c, 0.0);
                } else {
                    // Loose band (±15 %, about 11 standard deviations): catches unreachable or
                    // strongly favoured pairs; the samplers' chi-square tests check the rest.
                    assert!(
                        (c - expected).abs() < 0.15 * expected,
                        "pair ({a}, {b}) seen {c} times, expected {expected}"
                    );
                }
            }
        }
    }

    #[test]
    fn every_index_lands_everywhere_equally_often() {
        // Unbiased samplers need P(permute(i) = j) = 1 / len over random keys, for every i and j.
        for len in [2_u32, 3, 5, 6, 16, 17, 100] {
            let keys = 4_000 * len;
            for index in [0, len / 2, len - 1] {
                let mut counts = vec![0_u32; len as usize];
                for key in 0..keys {
                    counts[permute(index, len, key.wrapping_mul(0x2545_F491)) as usize] += 1;
                }
                for (j, &c) in counts.iter().enumerate() {
                    // Expected 4000, standard deviation under 64: a ±10 % band is over 6 sigma.
                    assert!(
                        c.abs_diff(4_000) < 400,
                        "len {len}: {index} -> {j} {c} times"
                    );
                }
            }
        }
    }

    #[test]
    fn hash2_is_order_sensitive() {
        assert_ne!(hash2(1, 2), hash2(2, 1));
        assert_ne!(hash2(0, 0), hash2(0, 1));
    }
}
