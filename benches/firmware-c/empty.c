/* The baseline every firmware carries: the reset vector and a loop. */
void reset_handler(void);

void reset_handler(void)
{
    for (;;) {
    }
}
