-- A syntax error: the post stops before it reads the CL.
function on_block(text, ctx)
  return text:gsub("G28", "G30"
end
