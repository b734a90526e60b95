function on_block(text)
  while true do pcall(function() while true do end end) end
end
