/* ---- Stream decoder ---- */

const char *${lo}reject_name(${lo}reject reason)
{
    switch (reason) {
    case ${up}REJECT_BAD_HEADER: return "bad header";
    case ${up}REJECT_BAD_HEADER_CHECK: return "bad header check";
    case ${up}REJECT_BAD_LENGTH: return "bad length";
    case ${up}REJECT_BAD_CHECKSUM: return "bad checksum";
    case ${up}REJECT_BAD_TRAILER: return "bad trailer";
${escape_name}    case ${up}REJECT_TRUNCATED: return "truncated frame";
    default: return NULL;
    }
}

${up}UNUSED static void ${lo}count_reject(${lo}stats *s, int reason)
{
    s->skipped_bytes++;
    switch (reason) {
    case ${up}REJECT_BAD_HEADER: s->bad_header++; break;
${escape_count}    case ${up}REJECT_BAD_HEADER_CHECK: s->bad_header_check++; break;
    case ${up}REJECT_BAD_LENGTH: s->bad_length++; break;
    case ${up}REJECT_BAD_CHECKSUM: s->bad_checksum++; break;
    case ${up}REJECT_BAD_TRAILER: s->bad_trailer++; break;
    default: s->truncated++; break;
    }
}
