-- Framing: the frame layouts of the spec executed over a byte buffer (a Lua table indexed
-- from 0), as the stream engine of the runtime executes them: the sync, the length rule,
-- the constants, the header checks, the frame checks and the markers, in that order.

-- A position of the layout ({s = n} from the start, {e = n} back from the end) in a frame of
-- `len` bytes, or nil outside it.
function resolve(pos, len)
  if pos.s then
    if pos.s <= len then return pos.s end
    return nil
  end
  if pos.e <= len then return len - pos.e end
  return nil
end

-- The unsigned integer of `size` bytes at buf[at] (exact up to 6 bytes).
function read_uint(buf, at, size, order)
  local v = 0
  if order == "be" then
    for i = 0, size - 1 do v = v * 256 + buf[at + i] end
  else
    for i = size - 1, 0, -1 do v = v * 256 + buf[at + i] end
  end
  return v
end

-- A word field (a header value, a key, a flag) of the frame at `s`, of `len` bytes.
function read_field(f, buf, s, len)
  local at = resolve(f.at, len)
  if not at or at + f.size > len then return nil end
  local word = read_uint(buf, s + at, f.size, f.order)
  return math.floor(word / 2 ^ f.shift) % 2 ^ f.width
end

local function sync_len(fmt)
  if #fmt.sync_set > 0 then return #fmt.sync + 1 end
  return #fmt.sync
end

-- Whether the bytes at `s` (`avail` of them) start as a frame of `fmt` does, as far as they go.
local function sync_matches(fmt, buf, s, avail)
  local k = 0
  if #fmt.sync_set > 0 then
    if avail < 1 then return true end
    if not fmt.sync_lookup[buf[s]] then return false end
    k = 1
  end
  for i, b in ipairs(fmt.sync) do
    if k + i > avail then return true end
    if buf[s + k + i - 1] ~= b then return false end
  end
  return true
end

-- The format of the link a candidate at `s` is probed as: the first whose sync it matches.
function select_format(buf, s, avail)
  for _, fi in ipairs(SPEC.link) do
    if sync_matches(SPEC.formats[fi], buf, s, avail) then return fi end
  end
  return SPEC.link[1]
end

-- The total and body lengths (body: without a flag trailer) of a frame by its length rule,
-- "need" and a count when more bytes must come, or nil for a bad length.
local function measure(fmt, buf, s, span, avail)
  local L = fmt.length
  if L.fixed then return L.fixed, L.fixed end
  local count = read_field(L.field, buf, s, span)
  if count == nil then return nil end
  local extra = 0
  if L.extension then
    local e = L.extension
    if count == e.marker then
      local needed = e.wide.at.s + e.wide.size
      if avail < needed then return "need", needed end
      count = read_field(e.wide, buf, s, needed)
      if count < e.marker then return nil end
      extra = e.len
    elseif count > e.marker then
      return nil
    end
  end
  local body = count + L.adjust + extra
  local total = body
  if L.trailer and read_field(L.trailer.flag, buf, s, span) ~= 0 then
    total = body + L.trailer.len
  end
  return total, body
end

-- Examines the candidate at `s`: "frame", total and body lengths; "need" and a count; or
-- "reject" and the reason (with the failing check and its values for a bad check).
function probe(fmt, buf, s, avail)
  if not sync_matches(fmt, buf, s, avail) then return "reject", "bad header" end
  local span = math.max(fmt.decide_len, sync_len(fmt))
  if avail < span then return "need", span end
  for _, c in ipairs(fmt.constants) do
    if read_field(c.field, buf, s, span) ~= c.value then return "reject", "bad header" end
  end
  for _, ci in ipairs(fmt.header_checks) do
    local stored, computed = run_check(fmt.checks[ci], buf, s, span)
    if stored == nil or stored ~= computed then
      return "reject", "bad header check", ci, stored, computed
    end
  end
  local shortest = math.max(span, fmt.min_len, 1)
  local total, body = measure(fmt, buf, s, span, avail)
  if total == "need" then return "need", body end
  if total == nil then return "reject", "bad length" end
  if fmt.length.bare and total == fmt.length.bare and total >= span and total > 0 then
    return "frame", total, total
  end
  if total < shortest or total > fmt.max_len then return "reject", "bad length" end
  if avail < total then return "need", total end
  for _, ci in ipairs(fmt.frame_checks) do
    local stored, computed = run_check(fmt.checks[ci], buf, s, body)
    if stored == nil or stored ~= computed then
      return "reject", "bad checksum", ci, stored, computed
    end
  end
  for _, m in ipairs(fmt.markers) do
    local at = resolve(m.at, body)
    if not at or at + #m.bytes > body then return "reject", "bad trailer" end
    for i, b in ipairs(m.bytes) do
      if buf[s + at + i - 1] ~= b then return "reject", "bad trailer" end
    end
  end
  return "frame", total, body
end

-- Bytes of the wider length a marker value of the length field announces (0 without it).
function extension_len(fmt, buf, s, body)
  local e = fmt.length.extension
  if e and read_field(fmt.length.field, buf, s, body) == e.marker then return e.len end
  return 0
end
