-- One string.find the count hook cannot interrupt: refused before it starts.
local text = string.rep("a", 1e5)
function on_tool_change(tool)
  if text:find(".-.-.-.-b") then post.emit("M1") end
end
