//! The decoder's buffer as generated code sizes it (`decoder_buffer_len`): the size for the
//! target the tests run on, with room for a frame and a checksum window.

use protocol_runtime::decoder::{
    HOST_BUFFER_LEN, decoder_buffer_len, decoder_buffer_len_for, decoder_ram,
};

#[test]
fn the_buffer_is_this_targets_and_holds_a_frame_and_a_check_window() {
    let pointer_bytes = size_of::<usize>();
    let host = pointer_bytes >= 8;
    for max_frame in [1, 4, 64, 65, 127, 1024, 4096] {
        let len = decoder_buffer_len(max_frame);
        assert_eq!(len, decoder_buffer_len_for(max_frame, host), "{max_frame}");
        assert_eq!(
            len,
            decoder_ram(max_frame, pointer_bytes).buffer,
            "{max_frame}"
        );
        assert!(len >= max_frame + 128, "{max_frame}: {len}");
        assert!(!host || len >= HOST_BUFFER_LEN, "{max_frame}: {len}");
    }
}
