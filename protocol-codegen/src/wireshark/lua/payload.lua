-- Payloads: the structs of the spec read field by field from a payload buffer, each value
-- added to the tree under its own filterable field. A read that runs out of bytes stops with
-- an expert note, as the run-time codec stops with a payload-length error.

local function signed(raw, size)
  local half = 2 ^ (8 * size - 1)
  if raw >= half then return raw - 2 * half end
  return raw
end

-- The value of an IEEE 754 half's bits (Wireshark reads no 2-byte float).
local function half_value(raw)
  local sign = raw >= 0x8000 and -1 or 1
  local exp, man = math.floor(raw / 1024) % 32, raw % 1024
  if exp == 0 then return sign * man * 2 ^ -24 end
  if exp == 31 then
    if man == 0 then return sign * math.huge end
    -- 0/0 is a NaN of the platform's sign (negative on x86); the half's sign is kept.
    local nan = 0 / 0
    if (tostring(nan):sub(1, 1) == "-") ~= (sign < 0) then nan = -nan end
    return nan
  end
  return sign * (1 + man / 1024) * 2 ^ (exp - 15)
end

-- The raw value of a float element at ctx.off: a half from its bits, else as Wireshark reads
-- it.
local function float_value(e, ctx, range)
  if e.half then return half_value(read_uint(ctx.buf, ctx.off, e.size, e.order)) end
  if e.order == "le" then return range:le_float() end
  return range:float()
end

-- Adds one element of a scalar, enum or text type at ctx.off; returns its raw integer.
local function read_elem(e, ctx, tree)
  local size = e.size
  if ctx.off + size > ctx.limit then error("short", 0) end
  local range = ctx.tvb(ctx.off, size)
  local raw
  if e.text then
    local chars = {}
    for i = 0, size - 1 do
      local b = ctx.buf[ctx.off + i]
      if b == 0 then break end
      chars[#chars + 1] = string.char(b)
    end
    tree:add(e.pf, range, table.concat(chars))
  elseif e.scale and e.float then
    local value = float_value(e, ctx, range)
    local item = tree:add(e.pf, range, value * e.scale.factor + e.scale.offset)
    item:append_text(string.format(" (raw %s)", tostring(value)))
  elseif e.scale then
    raw = read_uint(ctx.buf, ctx.off, size, e.order)
    if e.signed then raw = signed(raw, size) end
    local item = tree:add(e.pf, range, raw * e.scale.factor + e.scale.offset)
    item:append_text(string.format(" (raw %d)", raw))
  elseif e.half then
    tree:add(e.pf, range, float_value(e, ctx, range))
  elseif e.inverted then
    -- An inverted bool: the byte 0 is true.
    tree:add(e.pf, range, ctx.buf[ctx.off] == 0)
  elseif e.order == "le" then
    tree:add_le(e.pf, range)
  else
    tree:add(e.pf, range)
  end
  if size <= 6 and not e.float and not e.text then
    raw = raw or read_uint(ctx.buf, ctx.off, size, e.order)
  end
  ctx.off = ctx.off + size
  return raw
end

local read_struct, payload_field

local function read_value(e, ctx, tree)
  if e.struct then
    local sub = tree:add(proto, ctx.tvb(ctx.off, 0), e.name .. ": " .. SPEC.structs[e.struct].name)
    local start = ctx.off
    read_struct(e.struct, ctx, sub)
    sub:set_len(ctx.off - start)
    return nil
  end
  return read_elem(e, ctx, tree)
end

-- One element of a bit-packed array (the runtime's get_packed).
local function packed_elem(buf, base, index, bits, msb)
  local start = index * bits
  local first, last, skip = math.floor(start / 8), math.ceil((start + bits) / 8), start % 8
  local word = 0
  if msb then
    for i = first, last - 1 do word = word * 256 + buf[base + i] end
    return math.floor(word / 2 ^ ((last - first) * 8 - skip - bits)) % 2 ^ bits
  end
  for i = last - 1, first, -1 do word = word * 256 + buf[base + i] end
  return math.floor(word / 2 ^ skip) % 2 ^ bits
end

-- Bit `k` (0 the least significant) of member `m` of a bits field `f` at buf[at]: a word's
-- bits count from its least significant bit, a stream's from the first byte's most
-- significant bit (the runtime's get_bits and get_stream).
local function member_bit(f, m, buf, at, k)
  local pos, byte, down
  if f.stream then
    pos = m.shift + m.width - 1 - k
    byte, down = math.floor(pos / 8), 7 - pos % 8
  else
    pos = m.shift + k
    byte, down = math.floor(pos / 8), pos % 8
    if f.order == "be" then byte = f.size - 1 - byte end
  end
  return math.floor(buf[at + byte] / 2 ^ down) % 2
end

-- The value of member `m`, two's complement of its width when signed: a Lua number up to 53
-- bits, which a double holds exactly, else a UInt64 or Int64 built from its two 32-bit halves.
-- Also the number a scaled member's physical value is computed from, rounded once, as the
-- runtime converts its integer.
local function member_value(f, m, buf, at)
  local hi, lo = 0, 0
  for k = m.width - 1, 0, -1 do
    local b = member_bit(f, m, buf, at, k)
    if k >= 32 then hi = hi * 2 + b else lo = lo * 2 + b end
  end
  local negative = m.signed and (m.width > 32 and hi or lo) >= 2 ^ ((m.width - 1) % 32)
  if m.width <= 53 then
    local v = hi * 2 ^ 32 + lo
    if negative then v = v - 2 ^ m.width end
    return v, v
  end
  if not m.signed then
    local v = UInt64.new(lo, hi)
    return v, v:tonumber()
  end
  -- Sign-extended to 64 bits: the bits above the member's are ones when it is negative.
  if negative then hi = hi + 2 ^ 32 - 2 ^ (m.width - 32) end
  local v = Int64.new(lo, hi)
  return v, v:tonumber()
end

-- The bytes member `m` lies in, as an offset from the field's start and a count.
local function member_bytes(f, m)
  if not f.stream then return 0, f.size end
  local first = math.floor(m.shift / 8)
  return first, math.floor((m.shift + m.width - 1) / 8) - first + 1
end

local function read_bits(f, ctx, tree)
  if ctx.off + f.size > ctx.limit then error("short", 0) end
  local sub = tree:add(proto, ctx.tvb(ctx.off, f.size), f.name)
  for _, m in ipairs(f.members) do
    local v, number = member_value(f, m, ctx.buf, ctx.off)
    local from, len = member_bytes(f, m)
    local range = ctx.tvb(ctx.off + from, len)
    if m.scale then
      local item = sub:add(m.pf, range, number * m.scale.factor + m.scale.offset)
      if type(v) == "number" then v = string.format("%d", v) end
      item:append_text(" (raw " .. tostring(v) .. ")")
    elseif m.bool then
      sub:add(m.pf, range, v ~= 0)
    elseif m.wide and type(v) == "number" then
      if m.signed then sub:add(m.pf, range, Int64.new(v)) else sub:add(m.pf, range, UInt64.new(v)) end
    else
      sub:add(m.pf, range, v)
    end
  end
  ctx.off = ctx.off + f.size
end

local function read_packed(f, ctx, tree)
  if ctx.off + f.size > ctx.limit then error("short", 0) end
  local range = ctx.tvb(ctx.off, f.size)
  local sub = tree:add(proto, range, f.name)
  for i = 0, f.count - 1 do
    local raw = packed_elem(ctx.buf, ctx.off, i, f.bits, f.msb)
    if f.scale then
      sub:add(f.pf, range, raw * f.scale.factor + f.scale.offset)
    else
      sub:add(f.pf, range, raw)
    end
  end
  ctx.off = ctx.off + f.size
end

-- The number of elements or bytes a sized field takes: the field it names, of its own
-- struct or of the struct that repeats it.
local function stated(f, values, owner)
  return (owner or values)[f.size_from] or 0
end

local function read_many(f, ctx, tree, values, owner)
  local sub = tree:add(proto, ctx.tvb(ctx.off, 0), f.name)
  local start = ctx.off
  if f.size_from then
    local n = stated(f, values, owner)
    if n > f.max then error("too many", 0) end
    for _ = 1, n do read_value(f.elem, ctx, sub) end
  else
    local n = 0
    while ctx.off < ctx.limit do
      if n == f.max then error("too many", 0) end
      read_value(f.elem, ctx, sub)
      n = n + 1
    end
  end
  sub:set_len(ctx.off - start)
end

-- The packet carrying bytes `n` at ctx.off carry (`carries`: the field holding its command's
-- id), read one level in the direction of the frame (`ctx.carry`) into a subtree of `item`:
-- its command, and its payload as the command's struct; one that is not is an expert note.
local function read_carried(f, ctx, item, values, n)
  local key = values[f.carries]
  local ci = key and SPEC.command_by_id[tonumber(tostring(key))]
  if not ci then
    item:add_proto_expert_info(EXPERT.unknown, "unknown carried command " .. tostring(key))
    return
  end
  local c = SPEC.commands[ci]
  local sub = item:add(proto, ctx.tvb(ctx.off, n), "carried: " .. c.name)
  sub:add(F_command, ctx.tvb(ctx.off, n), c.name)
  local si = c.payloads[ctx.carry]
  if not si then
    if n > 0 then sub:add_proto_expert_info(EXPERT.payload, "a command without payload has bytes") end
    return
  end
  local inner = { tvb = ctx.tvb, buf = ctx.buf, off = ctx.off, limit = ctx.off + n }
  local ok, why = pcall(read_struct, si, inner, sub)
  if not ok then
    sub:add_proto_expert_info(EXPERT.payload, "carried payload of " .. SPEC.structs[si].name .. ": " .. tostring(why))
  elseif inner.off < inner.limit then
    sub:add_proto_expert_info(EXPERT.payload, string.format("%d carried payload bytes left over", inner.limit - inner.off))
  end
end

local function read_bytes(f, ctx, tree, values, owner)
  local n
  if f.size_from then
    n = stated(f, values, owner)
  else
    n = ctx.limit - ctx.off - (f.keep or 0)
  end
  if n < 0 or n > f.max or ctx.off + n > ctx.limit then error("short", 0) end
  local item = tree:add(f.pf, ctx.tvb(ctx.off, n))
  if f.carries and ctx.carry then read_carried(f, ctx, item, values, n) end
  ctx.off = ctx.off + n
end

local function read_nul_text(f, ctx, tree)
  local chars = {}
  for i = 0, f.max do
    if ctx.off + i >= ctx.limit then error("short", 0) end
    local b = ctx.buf[ctx.off + i]
    if b == 0 then
      tree:add(f.pf, ctx.tvb(ctx.off, i + 1), table.concat(chars))
      ctx.off = ctx.off + i + 1
      return
    end
    chars[#chars + 1] = string.char(b)
  end
  error("text without its NUL", 0)
end

local function read_group(f, ctx, tree, values)
  local sub = tree:add(proto, ctx.tvb(ctx.off, 0), f.name)
  local start, n = ctx.off, 0
  while ctx.off < ctx.limit do
    if n == f.max then error("too many", 0) end
    local item = sub:add(proto, ctx.tvb(ctx.off, 0), string.format("[%d]", n))
    local at = ctx.off
    for _, ef in ipairs(SPEC.structs[f.elem].fields) do
      payload_field(ef, ctx, item, {}, values)
    end
    item:set_len(ctx.off - at)
    n = n + 1
  end
  sub:set_len(ctx.off - start)
end

local function read_payload_check(f, ctx, tree, starts, ends)
  if ctx.off + f.size > ctx.limit then error("short", 0) end
  local from, to = starts[f.first], ends[f.last]
  local stored = read_uint(ctx.buf, ctx.off, f.size, f.order)
  local computed = compute(f.algorithm, ctx.buf, from, to)
  local item = tree:add(f.pf, ctx.tvb(ctx.off, f.size), stored)
  if stored == computed then
    item:append_text(" [correct]")
  else
    item:append_text(string.format(" [incorrect, should be 0x%x]", computed))
    item:add_proto_expert_info(EXPERT.bad_check, "bad payload check " .. f.name)
  end
  ctx.off = ctx.off + f.size
end

-- Reads one field of a struct; `values` collects the integers later fields may take their
-- size from; `owner` is the struct that repeats this one (a group's elements).
payload_field = function(f, ctx, tree, values, owner, starts, ends)
  local k = f.kind
  if k == "padding" then
    if ctx.off + f.size > ctx.limit then error("short", 0) end
    ctx.off = ctx.off + f.size
  elseif k == "value" then
    if f.count then
      local sub = tree:add(proto, ctx.tvb(ctx.off, 0), f.name)
      local start = ctx.off
      for _ = 1, f.count do read_value(f.elem, ctx, sub) end
      sub:set_len(ctx.off - start)
    else
      values[f.name] = read_value(f.elem, ctx, tree)
    end
  elseif k == "optional" then
    if ctx.off < ctx.limit then payload_field(f.inner, ctx, tree, values, owner, starts, ends) end
  elseif k == "bits" then read_bits(f, ctx, tree)
  elseif k == "packed" then read_packed(f, ctx, tree)
  elseif k == "array" then read_many(f, ctx, tree, values, owner)
  elseif k == "bytes" then read_bytes(f, ctx, tree, values, owner)
  elseif k == "nul_text" then read_nul_text(f, ctx, tree)
  elseif k == "group" then read_group(f, ctx, tree, values)
  elseif k == "check" then read_payload_check(f, ctx, tree, starts, ends)
  end
end

read_struct = function(si, ctx, tree)
  local values, starts, ends = {}, {}, {}
  for i, f in ipairs(SPEC.structs[si].fields) do
    starts[i] = ctx.off
    payload_field(f, ctx, tree, values, nil, starts, ends)
    ends[i] = ctx.off
  end
end

-- Reads struct `si` from the whole of `tvb` (whose bytes are `buf`); a payload too short, or
-- with bytes left over, gets an expert note. `carry`: the direction a carried packet is read
-- in (nil: the carrying bytes alone).
function read_payload(si, tvb, buf, len, tree, carry)
  local ctx = { tvb = tvb, buf = buf, off = 0, limit = len, carry = carry }
  local ok, why = pcall(read_struct, si, ctx, tree)
  if not ok then
    tree:add_proto_expert_info(EXPERT.payload, "payload of " .. SPEC.structs[si].name .. ": " .. tostring(why))
  elseif ctx.off < len then
    tree:add_proto_expert_info(EXPERT.payload, string.format("%d payload bytes left over", len - ctx.off))
  end
  return ok
end
