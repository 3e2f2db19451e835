//! Bit-level building blocks of Owen-scrambled Sobol points: the first two Sobol dimensions and a
//! hash-based nested uniform (Owen) scramble, after Burley, "Practical Hash-based Owen Scrambling"
//! (JCGT 2020).
//!
//! A *fraction word* is a `u32` read as the binary fraction 0.b₃₁b₃₀…b₀: its bit 31 is the first
//! digit (weight 1/2). [`crate::rng::unit_f32_from_bits`] turns one into a float in [0, 1).

/// Sobol dimension 0 at `index` (the base-2 radical inverse, van der Corput), as a fraction word.
#[inline]
pub(crate) fn sobol_0(index: u32) -> u32 {
    index.reverse_bits()
}

/// Sobol dimension 1 at `index`, as a fraction word. With [`sobol_0`] it forms a (0, 2)-sequence in
/// base 2: every aligned block of 2ᵏ consecutive indices is a (0, k, 2)-net.
///
/// Its generator matrix is Pascal's triangle mod 2: digit j (weight 2^-(j+1)) is the xor of the index
/// bits i with C(i, j) odd, which by Lucas' theorem are the i whose binary digits include j's (i ⊇ j
/// as 5-bit sets). That xor over supersets is computed for all 32 digits at once by five word-wide
/// steps, one per bit of the digit position (a zeta transform over GF(2)), so no direction-number
/// table is needed.
#[inline]
pub(crate) fn sobol_1(index: u32) -> u32 {
    let mut digits = index;
    // Step b: every position j with bit b clear takes in the value at j + 2^b.
    digits ^= (digits >> 1) & 0x5555_5555;
    digits ^= (digits >> 2) & 0x3333_3333;
    digits ^= (digits >> 4) & 0x0F0F_0F0F;
    digits ^= (digits >> 8) & 0x00FF_00FF;
    digits ^= digits >> 16;
    // Digit j sits at bit j; a fraction word has it at bit 31 − j.
    digits.reverse_bits()
}

/// The Laine–Karras-style hash of Burley's scramble, with the constants of Vegdahl's improved
/// version ("Building a Better LK Hash", 2021): a bijection of `u32`, selected by `seed`, in which
/// output bit k is input bit k flipped by a function of the bits below k and the seed. (Each step
/// keeps that form: adding, multiplying by an odd number and xoring with a multiple by an even
/// number only carry information from low bits to high bits.)
#[inline]
pub(crate) fn laine_karras(mut x: u32, seed: u32) -> u32 {
    x ^= x.wrapping_mul(0x3D20_ADEA);
    x = x.wrapping_add(seed);
    x = x.wrapping_mul((seed >> 16) | 1);
    x ^= x.wrapping_mul(0x0552_6C56);
    x ^ x.wrapping_mul(0x53A2_2864)
}

/// A nested uniform (Owen) scramble of the fraction word `v`, selected by `seed`: each digit is
/// flipped or not by a hash of the digits before it (the more significant ones) and the seed.
///
/// A bijection of `u32` that maps every aligned block of 2ᵏ words (equal top 32 − k bits) onto an
/// aligned block, so it keeps every elementary interval's count of a point set, and with it the net
/// property; the hash is [`laine_karras`] over the reversed bits:
/// `owen_scramble(v, seed) = laine_karras(v.reverse_bits(), seed).reverse_bits()`.
#[inline]
pub(crate) fn owen_scramble(v: u32, seed: u32) -> u32 {
    laine_karras(v.reverse_bits(), seed).reverse_bits()
}

/// The randomisation of one output coordinate: an [`owen_scramble`] keyed by the low half of `key`,
/// then a random digital shift (xor) by its high half.
///
/// The hash scramble alone is not exactly uniform over its seed (its seed-dependent multiplier can
/// favour some low-order digits); the shift, itself a nested scramble that flips every digit
/// independently, makes each coordinate exactly uniform over a uniform `key` whatever the input.
#[inline]
pub(crate) fn randomise(v: u32, key: u64) -> u32 {
    owen_scramble(v, key as u32) ^ (key >> 32) as u32
}

/// [`randomise`] of two fraction words with their own keys, `[randomise(v[0], keys[0]),
/// randomise(v[1], keys[1])]`, with the last bit reversal of both words done by one 64-bit
/// reversal (on x86-64 a bit reversal is about a dozen instructions whatever the width).
#[inline]
pub(crate) fn randomise_pair(v: [u32; 2], keys: [u64; 2]) -> [u32; 2] {
    let hashed = |v: u32, key: u64| u64::from(laine_karras(v.reverse_bits(), key as u32));
    // Reversing 64 bits swaps the halves and reverses each: the low word ends up high.
    let reversed = ((hashed(v[1], keys[1]) << 32) | hashed(v[0], keys[0])).reverse_bits();
    [
        (reversed >> 32) as u32 ^ (keys[0] >> 32) as u32,
        reversed as u32 ^ (keys[1] >> 32) as u32,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic stream of test words.
    fn words(count: u32) -> impl Iterator<Item = u32> {
        (0..count).map(|i| crate::hash::mix32(i ^ 0x5BD1_E995))
    }

    /// Sobol dimension 1 from its generator matrix, built independently as Pascal's triangle mod 2.
    fn sobol_1_by_matrix(index: u32) -> u32 {
        let mut pascal = [[false; 32]; 32];
        for i in 0..32 {
            pascal[i][0] = true;
            for j in 1..=i {
                pascal[i][j] = pascal[i - 1][j - 1] ^ pascal[i - 1][j];
            }
        }
        let mut value = 0;
        for (i, row) in pascal.iter().enumerate() {
            if index >> i & 1 == 1 {
                for (j, &odd) in row.iter().enumerate() {
                    if odd {
                        value ^= 1 << (31 - j);
                    }
                }
            }
        }
        value
    }

    #[test]
    fn sobol_1_applies_pascals_triangle_mod_2() {
        // The published direction numbers of the first columns (Joe and Kuo's dimension 2).
        let columns = [
            0x8000_0000,
            0xC000_0000,
            0xA000_0000,
            0xF000_0000,
            0x8800_0000,
        ];
        for (i, column) in columns.into_iter().enumerate() {
            assert_eq!(sobol_1(1 << i), column, "column {i}");
        }
        for index in words(2_000).chain([0, 1, u32::MAX, 1 << 31, 0x8000_0001]) {
            assert_eq!(sobol_1(index), sobol_1_by_matrix(index), "index {index:#x}");
        }
    }

    #[test]
    fn randomise_pair_is_two_randomise_calls() {
        let keys: Vec<u64> = words(64)
            .zip(words(64).skip(7))
            .map(|(a, b)| (u64::from(a) << 32) | u64::from(b))
            .chain([0, u64::MAX, 1 << 63, 0xFFFF_FFFF])
            .collect();
        for v in words(64).chain([0, 1, u32::MAX, 1 << 31]) {
            for pair in keys.windows(2) {
                let w = v.rotate_left(11) ^ 0x9E37_79B9;
                assert_eq!(
                    randomise_pair([v, w], [pair[0], pair[1]]),
                    [randomise(v, pair[0]), randomise(w, pair[1])],
                    "v {v:#x}, w {w:#x}, keys {:#x} {:#x}",
                    pair[0],
                    pair[1]
                );
            }
        }
    }

    #[test]
    fn sobol_0_is_the_radical_inverse() {
        assert_eq!(sobol_0(1), 0x8000_0000);
        assert_eq!(sobol_0(2), 0x4000_0000);
        assert_eq!(sobol_0(3), 0xC000_0000);
        assert_eq!(sobol_0(6), 0x6000_0000);
    }

    #[test]
    fn owen_scramble_permutes_every_aligned_block() {
        // For each top-k prefix length, the scramble induces a bijection of prefixes: words with
        // equal top k bits map to words with equal top k bits, and distinct prefixes stay distinct.
        for seed in words(20).chain([0, u32::MAX]) {
            for k in [1_u32, 4, 8] {
                let mut image = vec![None; 1 << k];
                for prefix in 0..1_u32 << k {
                    for low in words(8).chain([0, u32::MAX]) {
                        let v = (prefix << (32 - k)) | (low >> k);
                        let scrambled = owen_scramble(v, seed) >> (32 - k);
                        let slot = &mut image[prefix as usize];
                        assert!(
                            slot.is_none_or(|s| s == scrambled),
                            "seed {seed:#x}, k {k}: prefix {prefix} maps to two prefixes"
                        );
                        *slot = Some(scrambled);
                    }
                }
                let mut targets: Vec<u32> = image.into_iter().map(Option::unwrap).collect();
                targets.sort_unstable();
                targets.dedup();
                assert_eq!(
                    targets.len(),
                    1 << k,
                    "seed {seed:#x}, k {k}: not a bijection"
                );
            }
        }
    }

    #[test]
    fn owen_scramble_flips_deep_digits_by_the_digits_above() {
        // Nested scrambling flips digit j by a hash of digits 0..j: two words that differ only in
        // their first digit must, over many seeds, get their second digit flipped differently about
        // half of the time (a digital shift alone would flip it the same way every time).
        let (a, b) = (0x0000_0000, 0x8000_0000);
        let seeds = 4_000;
        let differ = words(seeds)
            .filter(|&seed| (owen_scramble(a, seed) ^ owen_scramble(b, seed)) & 0x4000_0000 != 0)
            .count();
        // Binomial(4000, 1/2): standard deviation about 32; allow ±6 sigma.
        assert!(differ.abs_diff(2_000) < 190, "{differ} of {seeds}");
    }

    #[test]
    fn randomise_keeps_every_value_representable_below_one() {
        // Extreme inputs and keys: the fraction word may be anything, including all ones, and
        // `unit_f32_from_bits` must still give a value in [0, 1).
        let keys = [0, 1, u64::MAX, 0xFFFF_FFFF, 0xFFFF_FFFF_0000_0000, 1 << 63];
        for key in keys {
            for v in [0, 1, u32::MAX, 1 << 31, u32::MAX - 1] {
                let x = crate::rng::unit_f32_from_bits(randomise(v, key));
                assert!((0.0..1.0).contains(&x), "v {v:#x}, key {key:#x}: {x}");
            }
        }
        assert!(crate::rng::unit_f32_from_bits(u32::MAX) < 1.0);
    }
}
