-- Terminal escapes in a warning and an error: shown as \x1b, never sent to the terminal.
function on_tool_change(tool)
  post.warning("\27[2J\27]0;title\7cleared")
  post.error("stop \27[31mred")
end
