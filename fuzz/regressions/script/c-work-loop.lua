local s = string.rep("a", 1e6)
function on_block(text)
  while true do local i = s:find("b", 1, true) local u = s:upper() end
end
