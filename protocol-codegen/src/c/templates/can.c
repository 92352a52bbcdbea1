int ${xlo}decode_can(uint32_t id, bool extended, const uint8_t *data, size_t len, ${xlo}packet *out)
{
    uint8_t virt[13];
    if (extended != (${xup}CAN_EXTENDED != 0) || len > 8u) return ${up}ERR_FRAME;
    ${lo}set(virt, 4u, 1, id);
    virt[4] = (uint8_t)len;
    if (len > 0) memcpy(virt + 5, data, len);
    return ${xlo}decode(virt, 5u + len, out);
}

int ${xlo}encode_can(const ${xlo}packet *packet, uint32_t *id, uint8_t data[8])
{
    uint8_t virt[${xup}MAX_FRAME_LEN];
    int len = ${xlo}encode(packet, virt, sizeof virt);
    if (len < 0) return len;
    if (len < 5 || len > 13) return ${up}ERR_OUT_OF_RANGE;
    *id = (uint32_t)${lo}get(virt, 4u, 1);
    memcpy(data, virt + 5, (size_t)len - 5u);
    return len - 5;
}
