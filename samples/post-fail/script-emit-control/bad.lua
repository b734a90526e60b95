-- A NUL and an escape sequence in a block.
function on_block(text)
  if text:find("^T") then return text .. "\0\27[2J" end
end
