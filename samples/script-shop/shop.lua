-- The shop's additions to fanuc-0itd-twin (docs/scripting.md).

-- The shop's tool list, beside the machine file: "number,name" a line, a heading line first.
local names = {}
for line in post.read_file("tools.csv"):gmatch("[^\r\n]+") do
  local number, name = line:match("^%s*(%d+)%s*,%s*(.-)%s*$")
  if number then names[tonumber(number)] = name end
end

-- Tool uses per channel and tool, for the life count written at each program's end.
post.vars.uses = {}

-- A comment naming the tool after each tool change, and one use more of it.
function on_tool_change(tool)
  local name = names[tool.number]
  if name then
    post.emit(string.format("(T%02d %s)", tool.number, name))
  else
    post.warning(string.format("T%02d is not in tools.csv: no name comment", tool.number))
  end
  local uses = post.vars.uses[tool.channel] or {}
  post.vars.uses[tool.channel] = uses
  uses[tool.number] = (uses[tool.number] or 0) + 1
end

-- Tool changes at the second reference point (G30, the tool-change position of parameter
-- 1241) instead of the machine zero; the program's end (its footer, which on_block sees as
-- ctx.part "footer") still goes to G28, where the operator unloads the part.
function on_block(text, ctx)
  if ctx.part == "body" and text:sub(1, 4) == "G28 " then return "G30 " .. text:sub(5) end
end

-- Each tool's uses added to its common variable #6nn (#601 for T01): the control's count,
-- read by a macro that stops the machine when a tool's life is up. Not #5nn: #500 and #501
-- are the transfer's grip and approach positions, which the machine file reserves (a script
-- that writes one is refused; docs/emulator.md). #600-#699 need the control's extended common
-- variables (Fanuc 0i-D: #500-#999 with that option).
function on_program_end(ctx)
  local uses = post.vars.uses[ctx.channel]
  if not uses then return end
  local tools = {}
  for number in pairs(uses) do tools[#tools + 1] = number end
  table.sort(tools)
  for _, n in ipairs(tools) do
    post.emit(string.format("#6%02d=#6%02d+%d", n, n, uses[n]))
  end
end

-- PARTS_CATCHER/ON and /OFF (an NX user command): the catcher out before the part-off, in
-- again after it (Doosan M10/M11). Any other record the post does not know stops the post.
function on_record(rec)
  if rec.major == "PARTS_CATCHER" and rec.words[1] == "ON" then
    post.emit("M10")
  elseif rec.major == "PARTS_CATCHER" and rec.words[1] == "OFF" then
    post.emit("M11")
  else
    post.error(rec.major .. "/" .. table.concat(rec.words, ",") .. " is not a record of this shop")
  end
end
