-- Registration: where captures reach the dissector (a user link type for raw serial bytes,
-- the UDP and TCP ports of the preferences, SocketCAN frames for a CAN format), and how a
-- frame cut across packets is put back together on each.

proto.prefs.user_dlt = Pref.uint("User link type", 0,
  "n of DLT_USERn (0 to 15, link type 147 + n) that raw serial captures are written with")
proto.prefs.udp_ports = Pref.range("UDP ports", "", "UDP ports whose datagrams carry frames", 65535)
proto.prefs.tcp_ports = Pref.range("TCP ports", "", "TCP ports whose streams carry frames", 65535)
if SPEC.directions_given then
  local choices = {}
  for d, name in ipairs(SPEC.directions) do choices[d] = { d, name, d } end
  proto.prefs.direction = Pref.enum("Direction", 1,
    "The direction of the frames, which no header field tells", choices, false)
end

-- Raw serial: the bytes of a frame cut by the end of a packet, carried into the next one on
-- the first pass, and what each packet was given (so a second pass shows the same).
local pending, carried = nil, {}

function proto.init()
  pending, carried = nil, {}
end

local function bytes_of(tvb, prefix)
  local buf, n = {}, 0
  if prefix then
    for i = 0, #prefix do buf[i] = prefix[i] end
    n = #prefix + 1
  end
  local ba = tvb:bytes()
  for i = 0, ba:len() - 1 do buf[n + i] = ba:get_index(i) end
  return buf, n + ba:len()
end

local function as_tvb(tvb, buf, n, prefixed)
  if not prefixed then return tvb end
  local ba = ByteArray.new()
  ba:set_size(n)
  for i = 0, n - 1 do ba:set_index(i, buf[i]) end
  return ba:tvb("Serial bytes with the frame begun in earlier packets")
end

local PT_TCP = 2

function proto.dissector(tvb, pinfo, tree)
  pinfo.cols.protocol = SPEC.title
  pinfo.cols.info = ""
  local serial = pinfo.port_type ~= PT_TCP and pinfo.port_type ~= 3
  local prefix
  if serial then
    if pinfo.visited then
      prefix = carried[pinfo.number]
    else
      prefix = pending
      carried[pinfo.number] = prefix
    end
  end
  local buf, n = bytes_of(tvb, prefix)
  local view = as_tvb(tvb, buf, n, prefix ~= nil)
  local root = tree:add(proto, view(), SPEC.title)
  local off, need = dissect_stream(buf, n, view, pinfo, root)
  if off < n and pinfo.port_type == PT_TCP and not prefix then
    pinfo.desegment_offset = off
    -- An escaped frame needs bytes up to its closing flag, however many.
    if need == 0 then
      pinfo.desegment_len = DESEGMENT_ONE_MORE_SEGMENT
    else
      pinfo.desegment_len = need - (n - off)
    end
    -- The segment is this protocol's (0 would hand it to another dissector).
    return tvb:len()
  end
  if serial and not pinfo.visited then
    pending = nil
    if off < n then
      pending = {}
      for i = off, n - 1 do pending[i - off] = buf[i] end
    end
  end
  -- (A lone flag at the end of an escaped link's bytes opens what comes next: nothing is cut.)
  if off < n and need > 0 then
    local item = root:add(F_cut, view(off, n - off))
    item:add_proto_expert_info(EXPERT.cut, string.format(
      "%d bytes of a frame that needs %d", n - off, need))
  elseif n - off > 1 then
    local item = root:add(F_cut, view(off, n - off))
    item:add_proto_expert_info(EXPERT.cut, string.format(
      "%d bytes of a frame that no flag has closed yet", n - off))
  end
  return tvb:len()
end

local function register_ports()
  local udp, tcp = DissectorTable.get("udp.port"), DissectorTable.get("tcp.port")
  udp:remove_all(proto)
  tcp:remove_all(proto)
  udp:add(proto.prefs.udp_ports, proto)
  tcp:add(proto.prefs.tcp_ports, proto)
end

local user_dlt = nil

function proto.prefs_changed()
  register_ports()
  local encap = DissectorTable.get("wtap_encap")
  if user_dlt then encap:remove(user_dlt, proto) end
  user_dlt = wtap_encaps.USER0 + proto.prefs.user_dlt
  encap:add(user_dlt, proto)
end

user_dlt = wtap_encaps.USER0
DissectorTable.get("wtap_encap"):add(user_dlt, proto)

-- SocketCAN: a CAN frame whose id names a command of the CAN format, taken as the virtual
-- frame the spec describes (the id as a big-endian u32, the data length, the data).
if SPEC.can_format then
  local can_id, can_xtd = Field.new("can.id"), Field.new("can.flags.xtd")
  -- The command key of a CAN frame: the whole id, or the members of it (`can_id_bits`) that
  -- the format dispatches on, read as every frame's key is read.
  local function can_key(fmt, buf, body, id)
    if fmt.carries == "can" then return string.format("%d", id) end
    return command_key(fmt, buf, 0, body)
  end
  local function can_heuristic(tvb, pinfo, tree)
    local fmt = SPEC.formats[SPEC.can_format]
    local id, xtd = can_id(), can_xtd()
    if not id or (xtd and xtd.value) ~= fmt.extended then return false end
    local len = tvb:len()
    local buf = { [0] = math.floor(id.value / 16777216) % 256, math.floor(id.value / 65536) % 256,
      math.floor(id.value / 256) % 256, id.value % 256, len }
    local ba = tvb:bytes()
    for i = 0, len - 1 do buf[5 + i] = ba:get_index(i) end
    local verdict, total, body = probe(fmt, buf, 0, 5 + len)
    if verdict ~= "frame" or not fmt.commands[can_key(fmt, buf, body, id.value)] then
      return false
    end
    pinfo.cols.protocol = SPEC.title
    pinfo.cols.info = ""
    local view = as_tvb(tvb, buf, 5 + len, true)
    dissect_frame(SPEC.can_format, buf, view, 0, total, body, pinfo, tree)
    return true
  end
  proto:register_heuristic("can", can_heuristic)
end
