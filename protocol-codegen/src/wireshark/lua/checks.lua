-- Checks: every checksum and CRC the spec language has, computed over bytes of a frame,
-- and the rule that verifies a check where it is stored. A CRC runs bit by bit from its
-- Rocksoft parameters (width up to 32 bits), so any CRC of a spec needs no table here.

local band, bor, bxor = bit32.band, bit32.bor, bit32.bxor
local lshift, rshift = bit32.lshift, bit32.rshift

local function reflect(v, n)
  local r = 0
  for _ = 1, n do
    r = r * 2 + v % 2
    v = math.floor(v / 2)
  end
  return r
end

-- The CRC of buf[from .. to - 1], then of `extra` when given.
local function crc(a, buf, from, to, extra)
  local w = a.width
  local mask = 2 ^ w - 1
  local reg = a.init
  local function feed(b)
    if a.refin then b = reflect(b, 8) end
    for k = 7, 0, -1 do
      local inbit = band(rshift(b, k), 1)
      local top = band(rshift(reg, w - 1), 1)
      reg = band(lshift(reg, 1), mask)
      if bxor(inbit, top) == 1 then reg = bxor(reg, a.poly) end
    end
  end
  for i = from, to - 1 do feed(buf[i]) end
  if extra then feed(extra) end
  if a.refout then reg = reflect(reg, w) end
  return band(bxor(reg, a.xorout), mask)
end

local function sum(buf, from, to, modulus, init)
  local s = init or 0
  for i = from, to - 1 do s = (s + buf[i]) % modulus end
  return s
end

local function fletcher(buf, from, to, modulus)
  local a, b = 0, 0
  for i = from, to - 1 do
    a = (a + buf[i]) % modulus
    b = (b + a) % modulus
  end
  return b * 256 + a
end

-- The value of algorithm `a` over buf[from .. to - 1] (and a CRC's extra byte).
local function compute(a, buf, from, to, extra)
  local k = a.kind
  if k == "crc" then return crc(a, buf, from, to, extra) end
  if k == "sum8" then return sum(buf, from, to, 256) end
  if k == "sum_mod_255" then return sum(buf, from, to, 255) end
  if k == "sum" then return bxor(sum(buf, from, to, 2 ^ (8 * a.width), a.init), a.xorout) end
  if k == "fletcher16" then return fletcher(buf, from, to, 255) end
  if k == "fletcher16_mod256" then return fletcher(buf, from, to, 256) end
  local x = a.init or 0
  for i = from, to - 1 do x = bxor(x, buf[i]) end
  return x
end

-- A frame check of frame `s` resolved against `len` bytes: its stored and computed values
-- (computed is nil when the extra byte's key names no command), and where it is stored.
local function run_check(c, buf, s, len)
  local from, to, at = resolve(c.from, len), resolve(c.to, len), resolve(c.at, len)
  if not (from and to and at) or to < from or at + c.size > len then return nil end
  local stored = read_uint(buf, s + at, c.size, c.order)
  local extra
  if c.extra then
    local key = read_field(c.extra.key, buf, s + from, to - from)
    extra = key and c.extra.bytes[key]
    if not extra then return stored, nil, at end
  end
  return stored, compute(c.algorithm, buf, s + from, s + to, extra), at
end
