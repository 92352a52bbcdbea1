-- Packets: a checked frame taken apart by the packet rules of its format (acknowledgement,
-- dispatch key, direction, stuffing, zero-fill), and a byte stream cut into frames, skipped
-- bytes and rejected candidates, as the stream engine of the runtime cuts it (an escaped
-- link's stream is cut at its flags, in the next part).

local function slice(buf, from, to)
  local out = {}
  for i = from, to - 1 do out[i - from] = buf[i] end
  return out
end

local function byte_array(buf, len)
  local ba = ByteArray.new()
  ba:set_size(len)
  for i = 0, len - 1 do ba:set_index(i, buf[i]) end
  return ba
end

-- The payload without the bytes stuffing inserted, or nil when a pattern lacks its byte.
local function unstuff(st, buf, len)
  local out, o, i, n = {}, 0, 0, #st.after
  while i < len do
    out[o] = buf[i]
    o, i = o + 1, i + 1
    local ends = n > 0 and o >= n
    for k = 1, n do
      if not ends then break end
      ends = out[o - n + k - 1] == st.after[k]
    end
    if ends then
      if buf[i] ~= st.insert then return nil end
      i = i + 1
    end
  end
  return out, o
end

local function add_header(fmt, buf, tvb, s, body, tree)
  for _, v in ipairs(fmt.values) do
    local at = resolve(v.field.at, body)
    if at and at + v.field.size <= body then
      local raw = read_field(v.field, buf, s, body)
      if v.bool then raw = raw ~= 0 end
      tree:add(v.pf, tvb(s + at, v.field.size), raw)
    end
  end
end

local function add_checks(fmt, buf, tvb, s, body, tree)
  for _, c in ipairs(fmt.checks) do
    local len = body
    if c.header then len = fmt.decide_len end
    local stored, computed, at = run_check(c, buf, s, len)
    if stored then
      local item = tree:add(c.pf, tvb(s + at, c.size), stored)
      if stored == computed then
        item:append_text(" [correct]")
      else
        item:append_text(" [incorrect]")
        item:add_proto_expert_info(EXPERT.bad_check, "bad " .. c.name)
      end
    end
  end
  if fmt.flag_trailer then
    local t = fmt.flag_trailer
    if read_field(t.flag, buf, s, body) ~= 0 then tree:add(t.pf, tvb(s + body, t.len)) end
  end
end

-- The struct a command frame carries and the payload it is read from (unstuffed and
-- zero-filled as the format's rules say), or nil and why not.
local function payload_of(fmt, si, buf, from, to)
  local pbuf, plen = slice(buf, from, to), to - from
  if fmt.stuffing then
    pbuf, plen = unstuff(fmt.stuffing, pbuf, plen)
    if not pbuf then return nil, "invalid stuffing" end
  end
  local S = si and SPEC.structs[si]
  local fill = S and fmt.truncate_zeros
  if S and S.base_size and not fmt.extensions then
    if plen ~= S.base_size then
      return nil, string.format("payload of %d bytes, the format carries %d", plen, S.base_size)
    end
    fill = true
  end
  if fill and plen < S.size then
    for i = plen, S.size - 1 do pbuf[i] = 0 end
    plen = S.size
  end
  return pbuf, plen, (fmt.stuffing or fill) and true
end

local function add_payload(si, pbuf, plen, new, tvb, from, pinfo, tree, carry)
  local ptvb
  if new then
    ptvb = byte_array(pbuf, plen):tvb("Payload")
  else
    ptvb = tvb(from, plen):tvb()
  end
  if not si then
    if plen > 0 then tree:add_proto_expert_info(EXPERT.payload, "a command without payload has bytes") end
    return
  end
  local sub = tree:add(proto, ptvb(), "payload: " .. SPEC.structs[si].name)
  read_payload(si, ptvb, pbuf, plen, sub, carry)
end

-- The direction of a command frame: the one the user gives (a preference) for a spec whose
-- header does not tell it, else the first whose test the header passes.
local function direction_of(fmt, buf, s, body)
  if SPEC.directions_given then return proto.prefs.direction end
  if #fmt.directions == 0 then return 1 end
  for d, t in ipairs(fmt.directions) do
    local v = read_field(t.field, buf, s, body)
    if v and ((t.equals and v == t.equals) or (t.first and v >= t.first and v <= t.last)) then
      return d
    end
  end
  return nil
end

-- The dispatch key of a frame, as the format's `commands` are keyed: `"3"`, `"1,2"`.
local function command_key(fmt, buf, s, body)
  local key = {}
  for _, k in ipairs(fmt.key) do key[#key + 1] = string.format("%d", read_field(k, buf, s, body)) end
  return table.concat(key, ",")
end

local function add_command(fmt, buf, tvb, s, body, pinfo, tree)
  local key = command_key(fmt, buf, s, body)
  local ci = fmt.commands[key]
  if not ci then
    tree:add_proto_expert_info(EXPERT.unknown, "unknown command " .. key)
    pinfo.cols.info:append(" unknown(" .. key .. ")")
    return
  end
  local c = SPEC.commands[ci]
  tree:add(F_command, tvb(s, body), c.name)
  tree:append_text(", " .. c.name)
  pinfo.cols.info:append(" " .. c.name)
  local d = direction_of(fmt, buf, s, body)
  if not d then
    tree:add_proto_expert_info(EXPERT.unknown, "no direction tells this frame")
    return
  end
  if SPEC.directions[d] then tree:add(F_direction, tvb(s, body), SPEC.directions[d]) end
  local si = c.payloads[d] or nil
  if si == false then si = nil end
  local from = fmt.header_len + extension_len(fmt, buf, s, body)
  local to = body - fmt.trailer_len
  local pbuf, plen, new = payload_of(fmt, si, buf, s + from, s + to)
  if not pbuf then
    tree:add_proto_expert_info(EXPERT.payload, plen)
    return
  end
  add_payload(si, pbuf, plen, new, tvb, s + from, pinfo, tree, d)
end

-- Acknowledgements: the flag set, the data after the shorter header.
local function add_ack(fmt, buf, tvb, s, total, body, tree)
  local a = fmt.ack
  if not a or read_field(a.flag, buf, s, body) ~= a.equals then return false end
  local stop = body - fmt.trailer_len
  if a.bare and total == a.header_len then stop = total end
  tree:add(F_ack, tvb(s, total), true)
  tree:append_text(", acknowledgement")
  if stop > a.header_len then tree:add(F_data, tvb(s + a.header_len, stop - a.header_len)) end
  return true
end

-- One frame of format `fi` at buf[s], `total` bytes (`body` without a flag trailer); returns
-- its subtree.
function dissect_frame(fi, buf, tvb, s, total, body, pinfo, tree)
  local fmt = SPEC.formats[fi]
  local sub = tree:add(proto, tvb(s, total), SPEC.title .. " " .. fmt.name)
  sub:add(F_format, tvb(s, total), fmt.name)
  sub:add(F_frame, tvb(s, total))
  add_header(fmt, buf, tvb, s, body, sub)
  add_checks(fmt, buf, tvb, s, body, sub)
  if add_ack(fmt, buf, tvb, s, total, body, sub) then return sub end
  local given = SPEC.directions_given and SPEC.directions[proto.prefs.direction]
  local message = given and SPEC.direction_messages[proto.prefs.direction]
  if message and fmt.carries == "command" then
    local from, to = message.start, body - fmt.trailer_len
    local pbuf, plen = payload_of(fmt, nil, buf, s + from, s + to)
    sub:add(F_direction, tvb(s, total), given)
    add_payload(message.struct, pbuf, plen, fmt.stuffing, tvb, s + from, pinfo, sub)
  elseif fmt.carries == "command" or fmt.carries == "can" then
    add_command(fmt, buf, tvb, s, body, pinfo, sub)
  elseif fmt.carries == "struct" then
    local from, to = fmt.header_len + extension_len(fmt, buf, s, body), body - fmt.trailer_len
    local pbuf, plen, new = payload_of(fmt, fmt.struct, buf, s + from, s + to)
    if pbuf then add_payload(fmt.struct, pbuf, plen, new, tvb, s + from, pinfo, sub) end
  else
    sub:add(F_data, tvb(s + fmt.header_len, body - fmt.header_len - fmt.trailer_len))
  end
  return sub
end

-- Bytes tvb(from, to - from) between frames, skipped.
function add_skipped(tvb, from, to, tree)
  local item = tree:add(F_skipped, tvb(from, to - from))
  item:add_proto_expert_info(EXPERT.skipped, string.format("%d bytes skipped", to - from))
end

-- A candidate of format `fmt` at tvb(at, len) rejected for `reason`; a bad check names the
-- check (the probe's `ci`) with its stored and computed values.
function add_rejected(fmt, tvb, at, len, reason, ci, stored, computed, tree)
  local item = tree:add(F_rejected, tvb(at, len), reason)
  if reason == "bad checksum" or reason == "bad header check" then
    item:add_proto_expert_info(EXPERT.bad_check, string.format(
      "%s: %s stored 0x%x, computed %s", reason, fmt.checks[ci].name, stored or 0,
      computed and string.format("0x%x", computed) or "nothing (no extra byte for the key)"))
  else
    item:add_proto_expert_info(EXPERT.skipped, reason)
  end
end

-- Whether a whole frame starts after `s` in the bytes a candidate at `s` waits for.
local function frame_inside(buf, s, n)
  for j = s + 1, n - 1 do
    if probe(SPEC.formats[select_format(buf, j, n - j)], buf, j, n - j) == "frame" then
      return true
    end
  end
  return false
end

-- Cuts buf[0 .. n - 1] into frames. Returns the offset of a frame cut by the end of the bytes
-- and the bytes it needs, or n when every byte is decided.
function dissect_stream(buf, n, tvb, pinfo, tree)
  local off, skipped = 0, nil
  local first = SPEC.link[1]
  if SPEC.formats[first].escape then return dissect_escaped(first, buf, n, tvb, pinfo, tree) end
  local function flush(to)
    if skipped then
      add_skipped(tvb, skipped, to, tree)
      skipped = nil
    end
  end
  while off < n do
    local fi = select_format(buf, off, n - off)
    local verdict, a, b, stored, computed = probe(SPEC.formats[fi], buf, off, n - off)
    if verdict == "frame" then
      flush(off)
      dissect_frame(fi, buf, tvb, off, a, b, pinfo, tree)
      off = off + a
    elseif verdict == "need" and not frame_inside(buf, off, n) then
      flush(off)
      return off, a
    elseif verdict == "need" then
      -- A frame complete inside the bytes a candidate waits for cuts it short, as the
      -- runtime's engine rejects such a candidate as truncated.
      flush(off)
      local item = tree:add(F_rejected, tvb(off, 1), "truncated")
      item:add_proto_expert_info(EXPERT.skipped, "a frame cut short by the next one")
      skipped = off
      off = off + 1
    else
      if a == "bad checksum" or a == "bad header check" then
        flush(off)
        add_rejected(SPEC.formats[fi], tvb, off, 1, a, b, stored, computed, tree)
      end
      skipped = skipped or off
      off = off + 1
    end
  end
  flush(off)
  return n, 0
end
