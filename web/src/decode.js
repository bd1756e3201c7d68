// Decoding the page's compact encoding (docs/report.md, "Encoding"): base64 text into typed arrays.

/** The bytes of a base64 text. */
export function bytes(b64) {
  const s = atob(b64);
  const out = new Uint8Array(s.length);
  for (let i = 0; i < s.length; i++) out[i] = s.charCodeAt(i);
  return out;
}

export function float32(b64) {
  const u = bytes(b64);
  return new Float32Array(u.buffer, 0, u.length >> 2);
}

export function int32(b64) {
  const u = bytes(b64);
  return new Int32Array(u.buffer, 0, u.length >> 2);
}

/**
 * An int16-channel object {rows, channels, offset, scale, int16} as a Float64Array of rows x channels
 * (value = offset[c] + scale[c] * int16).
 */
export function channels(e) {
  const u = bytes(e.int16);
  const n = e.rows * e.channels;
  const q = new Int16Array(u.buffer, 0, n);
  const out = new Float64Array(n);
  const c = e.channels;
  for (let i = 0; i < n; i++) out[i] = e.offset[i % c] + e.scale[i % c] * q[i];
  return out;
}

/** Index k of the last time <= t in the sorted array `times` (0 before the first), and the fraction to k + 1. */
export function locate(times, t) {
  const n = times.length;
  if (n === 0 || t <= times[0]) return { k: 0, a: 0 };
  if (t >= times[n - 1]) return { k: n - 1, a: 0 };
  let lo = 0, hi = n - 1;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (times[mid] <= t) lo = mid; else hi = mid;
  }
  const span = times[hi] - times[lo];
  return { k: lo, a: span > 0 ? (t - times[lo]) / span : 0 };
}
