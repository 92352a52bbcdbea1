/* The vector table: the initial stack pointer (the end of RAM) and the reset handler. */
void reset_handler(void);

__attribute__((section(".vector_table"), used)) void (*const vector_table[2])(void) = {
    (void (*)(void))0x20010000u,
    reset_handler,
};
