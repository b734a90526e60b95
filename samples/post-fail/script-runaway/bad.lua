-- A script that never returns: the instruction budget stops it.
function on_tool_change(tool)
  local n = 0
  while true do n = n + 1 end
end
