/* ---- Stream decoder ---- */

/** Why a candidate frame was rejected. */
typedef enum ${lo}reject {
    ${up}REJECT_BAD_HEADER = 1,   /**< The sync bytes or a constant of the header do not match. */
    ${up}REJECT_BAD_HEADER_CHECK, /**< A header check does not match. */
    ${up}REJECT_BAD_LENGTH,       /**< The length is outside the format's bounds. */
    ${up}REJECT_BAD_CHECKSUM,     /**< A frame check does not match. */
    ${up}REJECT_BAD_TRAILER,      /**< A trailer does not match. */
${escape_reason}    ${up}REJECT_TRUNCATED         /**< The frame's bytes never came. */
} ${lo}reject;

/** The name of a rejection reason. */
const char *${lo}reject_name(${lo}reject reason);

/** What a decoder counted: every byte fed is in `frame_bytes` or `skipped_bytes` once it
 *  is no longer pending (a rejected candidate's first byte is skipped). */
typedef struct ${lo}stats {
    uint64_t frames, frame_bytes, skipped_bytes;
    uint64_t bad_header, bad_header_check, bad_length, bad_checksum, bad_trailer, truncated;
} ${lo}stats;

typedef enum ${lo}event_kind {
    ${up}EVENT_FRAME = 1, /**< A valid frame: `bytes`, `len` (valid until the next call). */
    ${up}EVENT_REJECTED,  /**< A candidate at `offset` was rejected for `reason`. */
    ${up}EVENT_SKIPPED    /**< `len` bytes at `offset` where no candidate starts. */
} ${lo}event_kind;

typedef struct ${lo}event {
    ${lo}event_kind kind;
    int format;          /**< A frame's format (its index in the spec's frame formats). */
    uint64_t offset;     /**< Stream offset of the first byte. */
    size_t len;
    const uint8_t *bytes;
    ${lo}reject reason;
} ${lo}event;
