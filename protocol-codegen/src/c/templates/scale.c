/* `x` cut toward zero (NaN: 0). */
${up}UNUSED static ${ty} ${lo}cut_${sfx}(${ty} x)
{
    if (x != x) return ${zero};
${cut}}

${up}UNUSED static ${ty} ${lo}mag_${sfx}(${ty} x)
{
    return x >= ${zero} ? x : -x;
}

/* `raw * factor + offset`; `raw / n + offset` when `factor` is the reciprocal of an integer
 * `n` within float noise. */
${up}UNUSED static ${ty} ${lo}to_physical_${sfx}(${ty} raw, ${ty} factor, ${ty} offset)
{
    ${ty} inv = ${one} / factor;
    ${ty} n = ${lo}cut_${sfx}(inv >= ${zero} ? inv + ${half} : inv - ${half});
    ${ty} off = ${lo}mag_${sfx}(inv - n);
    ${ty} t;
    if (n != ${zero} && off <= ${noise} * ${lo}mag_${sfx}(n)) {
        t = raw / n;
    } else {
        t = raw * factor;
    }
    return t + offset;
}

/* The inverse of `to_physical` for a float on the wire: `(physical - offset) / factor`,
 * times `n` where `to_physical` divides by it; not rounded. */
${up}UNUSED static ${ty} ${lo}unscale_${sfx}(${ty} physical, ${ty} factor, ${ty} offset)
{
    ${ty} inv = ${one} / factor;
    ${ty} n = ${lo}cut_${sfx}(inv >= ${zero} ? inv + ${half} : inv - ${half});
    ${ty} off = ${lo}mag_${sfx}(inv - n);
    ${ty} d = physical - offset;
    if (n != ${zero} && off <= ${noise} * ${lo}mag_${sfx}(n)) {
        return d * n;
    }
    return d / factor;
}

/* Whether a decoded value lies in the clamp range, with the slack of its rounding. */
${up}UNUSED static int ${lo}within_${sfx}(${ty} x, ${ty} lo, ${ty} hi)
{
    ${ty} range = hi - lo;
    ${ty} slack = ${slack} * (range > ${one} ? range : ${one});
    return x >= lo - slack && x <= hi + slack;
}

${up}UNUSED static ${ty} ${lo}clamp_${sfx}(${ty} x, ${ty} lo, ${ty} hi)
{
    if (x < lo) return lo;
    if (x > hi) return hi;
    return x;
}

/* `(physical - offset) / factor`, rounded to nearest (halves away from zero; the cast cuts
 * it) or truncated (a quotient within float noise of an integer is that integer). */
${up}UNUSED static ${ty} ${lo}quantize_${sfx}(${ty} physical, ${ty} factor, ${ty} offset, int truncate)
{
    ${ty} q = (physical - offset) / factor;
    ${ty} nearest = q >= ${zero} ? q + ${half} : q - ${half};
    ${ty} cut, off, m;
    if (!truncate) return nearest;
    cut = ${lo}cut_${sfx}(nearest);
    off = ${lo}mag_${sfx}(q - cut);
    m = ${lo}mag_${sfx}(q) + ${lo}mag_${sfx}(offset / factor);
    if (off <= ${noise} * (m > ${one} ? m : ${one})) return cut;
    return q;
}
