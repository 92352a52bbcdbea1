/** ${what}: a fixed buffer of the largest frame, no heap. */
typedef struct ${dlo}decoder {
    size_t start, end;   /**< The pending bytes are buf[start..end]. */
    uint64_t position;   /**< Bytes taken from all inputs. */
${escape_state}    ${lo}stats stats;
    uint8_t buf[${dup}DECODER_BUFFER_LEN];
} ${dlo}decoder;

/** Makes a decoder empty, its counters zero. */
void ${dlo}decoder_init(${dlo}decoder *d);

/** The next event, taking bytes from `*input` (advanced, `*len` decreased): 1 with `*event`
 *  set, or 0 when the input is used up and the decoder waits for more. */
int ${dlo}decoder_next(${dlo}decoder *d, const uint8_t **input, size_t *len, ${lo}event *event);

/** Declares the end of the input: the next event among the pending bytes (a pending
 *  candidate is rejected as truncated). Call until it returns 0. */
int ${dlo}decoder_flush(${dlo}decoder *d, ${lo}event *event);
