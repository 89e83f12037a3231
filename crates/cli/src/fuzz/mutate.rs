//! Seeded mutations of a corpus input: bit flips, byte edits, truncation, deletion,
//! duplication of a span or a line (deep nesting, long lists), splicing with another input,
//! and the replacement of a numeric token by an extreme (1e300, -0, NaN, huge integers, …).

use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// Longest mutated input (bytes).
pub const MAX_LEN: usize = 256 << 10;

/// Numbers a careless or hostile user might type.
const EXTREMES: [&str; 24] = [
    "1e300",
    "-1e300",
    "1e-300",
    "-0",
    "0",
    "-0.0",
    "NaN",
    "nan",
    "inf",
    "-inf",
    "1e7",
    "1e9",
    "-1",
    "1",
    "2",
    "18446744073709551615",
    "18446744073709551616",
    "9223372036854775807",
    "-9223372036854775808",
    "4294967296",
    "99999999999999999999999",
    "0.000000001",
    "1e-9",
    "3.4e38",
];

/// Tokens that break the structure of the text formats.
const SYNTAX: [&str; 16] = [
    "<",
    ">",
    "</joint>",
    "<link name=\"x\"/>",
    "[",
    "]",
    "{",
    "}",
    "\"",
    "=",
    ",",
    "\n",
    "#",
    "'",
    "\u{feff}",
    "\r",
];

/// Whether `b` can be part of a number.
fn numeric(b: u8) -> bool {
    b.is_ascii_digit() || matches!(b, b'.' | b'-' | b'+' | b'e' | b'E')
}

/// Byte ranges of the numeric tokens of `input` (runs that hold a digit).
fn numbers(input: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < input.len() {
        if input[i].is_ascii_digit()
            || (input[i] == b'-' && input.get(i + 1).is_some_and(u8::is_ascii_digit))
        {
            let start = i;
            while i < input.len() && numeric(input[i]) {
                i += 1;
            }
            out.push((start, i));
        } else {
            i += 1;
        }
    }
    out
}

fn span(rng: &mut ChaCha8Rng, len: usize) -> (usize, usize) {
    let a = rng.random_range(0..=len);
    let b = rng.random_range(a..=len.min(a + 64.max(len / 8)));
    (a, b)
}

/// One to four mutations of `input`; `other` is another input of the same loader (splicing).
pub fn mutate(rng: &mut ChaCha8Rng, input: &[u8], other: &[u8]) -> Vec<u8> {
    let mut v = input.to_vec();
    for _ in 0..rng.random_range(1..=4) {
        let len = v.len();
        match rng.random_range(0..12) {
            // The most telling edit for parsers of numbers: an extreme value.
            0..=3 => {
                let nums = numbers(&v);
                if nums.is_empty() {
                    continue;
                }
                let (a, b) = nums[rng.random_range(0..nums.len())];
                let x = EXTREMES[rng.random_range(0..EXTREMES.len())];
                v.splice(a..b, x.bytes());
            }
            4 if len > 0 => {
                let i = rng.random_range(0..len);
                v[i] ^= 1 << rng.random_range(0..8);
            }
            5 if len > 0 => {
                let i = rng.random_range(0..len);
                v[i] = rng.random();
            }
            6 => v.truncate(rng.random_range(0..=len)),
            7 => {
                let (a, b) = span(rng, len);
                v.drain(a..b);
            }
            8 => {
                // A span repeated: long lists, deep nesting.
                let (a, b) = span(rng, len);
                let times = 1 << rng.random_range(0..10);
                let piece = v[a..b].to_vec();
                for _ in 0..times {
                    if v.len() + piece.len() > MAX_LEN {
                        break;
                    }
                    v.splice(b..b, piece.iter().copied());
                }
            }
            9 if !other.is_empty() => {
                let (a, b) = span(rng, other.len());
                let at = rng.random_range(0..=len);
                v.splice(at..at, other[a..b].iter().copied());
            }
            10 => {
                let at = rng.random_range(0..=len);
                let t = SYNTAX[rng.random_range(0..SYNTAX.len())];
                v.splice(at..at, t.bytes());
            }
            _ => {
                // A little-endian word set to an extreme (lengths and counts of binary files).
                if len >= 8 {
                    let i = rng.random_range(0..=len - 8);
                    let w: u64 = match rng.random_range(0..4) {
                        0 => u64::MAX,
                        1 => 0,
                        2 => 1 << rng.random_range(0..64),
                        _ => rng.random(),
                    };
                    let bytes = w.to_le_bytes();
                    let k = [1, 2, 4, 8][rng.random_range(0..4)];
                    v[i..i + k].copy_from_slice(&bytes[..k]);
                }
            }
        }
        v.truncate(MAX_LEN);
    }
    v
}
