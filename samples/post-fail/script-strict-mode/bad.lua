-- The strict-mode idiom: an undefined global is an error, not a crash of the post.
setmetatable(_ENV, {__index = function(_, k) error("undefined global " .. k, 2) end})
function on_tool_change(tool)
  post.emit("(TOOL " .. tool.number .. " " .. tool_name .. ")")
end
