-- A wait code written into channel 1 only: channel 2 never meets it.
function on_tool_change(tool)
  if tool.channel == 1 and tool.number == 3 then post.emit("M101") end
end
