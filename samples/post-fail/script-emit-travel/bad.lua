-- A move past the X travel, as a template's would be refused.
function on_tool_change(tool)
  post.emit("G0 X9000.")
end
