-- A tape mark mid-program: the control would stop reading there.
function on_tool_change(tool)
  if tool.number == 3 then post.emit("%") end
end
