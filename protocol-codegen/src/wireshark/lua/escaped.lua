-- Escaped links (HDLC, SLIP): a stream of frames escaped between flags, cut as the runtime's
-- escaped path cuts it. Bytes before a flag are skipped; a flag opens a candidate; the bytes
-- after it are unescaped as they come; the next flag closes it, and the format's ordinary
-- rules decide the unescaped bytes, which are dissected as a data source of their own
-- ("Unescaped"): lengths and checks count and cover them. A flag is always a boundary, and
-- the flag that closes a frame opens the next candidate.

-- The candidate at buf[s] (a flag), unescaped: "closed", its bytes, their count and the
-- offset of the closing flag; "lone" and the offset of a flag right after the first; "cut"
-- when the bytes end first; or "reject", the reason and where the hunt for a flag resumes.
local function unescape_at(fmt, buf, s, n)
  local e = fmt.escape
  local out, o, escaped = { [0] = e.flag }, 1, false
  for i = s + 1, n - 1 do
    local b = buf[i]
    if b == e.flag then
      -- A flag after the escape byte damages the candidate; the flag opens the next one.
      if escaped then return "reject", "bad escape", i end
      if o == 1 then return "lone", i end
      out[o] = b
      return "closed", out, o + 1, i
    end
    if escaped then
      local original = e.original[b]
      if not original then return "reject", "bad escape", i + 1 end
      out[o], o, escaped = original, o + 1, false
    elseif b == e.escape then
      escaped = true
    else
      out[o], o = b, o + 1
    end
    -- A candidate longer than a frame may be is rejected without waiting for its flag.
    if o > fmt.max_len then return "reject", "bad length", i + 1 end
  end
  return "cut"
end

-- The candidate unescaped into `ubuf` (`len` bytes, wire bytes tvb(s, to - s)), a frame of
-- format `fi` when its rules take all of it, else a rejected candidate. Whether it is a frame.
local function decide_escaped(fi, ubuf, len, tvb, s, to, pinfo, tree)
  local fmt = SPEC.formats[fi]
  local verdict, total, body, stored, computed = probe(fmt, ubuf, 0, len)
  if verdict == "frame" and total == len then
    local view = ByteArray.new()
    view:set_size(len)
    for i = 0, len - 1 do view:set_index(i, ubuf[i]) end
    local sub = dissect_frame(fi, ubuf, view:tvb("Unescaped"), 0, total, body, pinfo, tree)
    sub:add(F_escaped, tvb(s, to - s))
    return true
  end
  if verdict ~= "reject" then total = "bad length" end
  add_rejected(fmt, tvb, s, to - s, total, body, stored, computed, tree)
  return false
end

-- Cuts buf[0 .. n - 1] of the escaped link format `fi` into frames. Returns the offset of a
-- candidate no flag has closed yet, and 0 (it needs bytes up to a flag), or n.
function dissect_escaped(fi, buf, n, tvb, pinfo, tree)
  local flag = SPEC.formats[fi].escape.flag
  -- `counted`: the flag at `off` closed a frame, and belongs to it if no frame follows.
  local off, skipped, counted = 0, nil, false
  local function flush(to)
    if skipped then add_skipped(tvb, skipped, to, tree) end
    skipped = nil
  end
  while off < n do
    if buf[off] ~= flag then
      skipped = skipped or off
      off, counted = off + 1, false
    else
      local verdict, a, b, c = unescape_at(SPEC.formats[fi], buf, off, n)
      if verdict == "cut" then
        flush(off)
        return off, 0
      elseif verdict == "lone" then
        if not counted then skipped = skipped or off end
        off, counted = a, false
      elseif verdict == "closed" then
        flush(off)
        counted = decide_escaped(fi, a, b, tvb, off, c + 1, pinfo, tree)
        off = c
      else
        flush(off)
        add_rejected(SPEC.formats[fi], tvb, off, b - off, a, nil, nil, nil, tree)
        off, counted = b, false
      end
    end
  end
  flush(off)
  return n, 0
end
