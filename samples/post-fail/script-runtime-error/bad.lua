-- A script run-time error: arithmetic on a field the tool table does not have.
function on_tool_change(tool)
  post.emit("#5" .. tool.number .. "=" .. tool.life + 1)
end
