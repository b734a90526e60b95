-- A T word past the control's format (T four digits on the 0i-TD).
function on_tool_change(tool)
  post.emit(string.format("T%d", tool.number * 100001))
end
