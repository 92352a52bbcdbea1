/* ---- Results: a negative int is one of these ---- */

/** The caller's buffer is too short for the frame. */
#define ${up}ERR_SHORT_BUFFER (-1)
/** A value does not fit its field (a bit member, a 24-bit integer, a scaled value whose raw
 *  integer does not fit its type, bytes or elements beyond their maximum or other than the
 *  length their size field states, text longer than its maximum or holding a NUL, an enum
 *  value without variant when the enum rejects them). */
#define ${up}ERR_OUT_OF_RANGE (-2)
/** The payload's size is not its command's. */
#define ${up}ERR_PAYLOAD_LENGTH (-3)
/** No command has the frame's dispatch key. */
#define ${up}ERR_UNKNOWN_COMMAND (-4)
/** The header matches no direction. */
#define ${up}ERR_UNKNOWN_DIRECTION (-5)
/** A field holds a value without variant of an enum that rejects them. */
#define ${up}ERR_INVALID_ENUM (-6)
/** The bytes are not exactly one valid frame (header, length, checks, trailers). */
#define ${up}ERR_FRAME (-7)
/** Sized bytes or an array whose stated length exceeds its maximum. */
#define ${up}ERR_SIZE_MISMATCH (-8)
/** NUL-terminated text without its NUL within its maximum. */
#define ${up}ERR_UNTERMINATED (-9)
/** A check inside the payload does not match its covered fields. */
#define ${up}ERR_PAYLOAD_CHECK (-10)
/** A scaled value outside its clamp range (it would not encode back to its bytes). */
#define ${up}ERR_OUTSIDE_CLAMP (-11)
/** A stuffed payload without the inserted byte after a run of the pattern. */
#define ${up}ERR_INVALID_STUFFING (-12)
