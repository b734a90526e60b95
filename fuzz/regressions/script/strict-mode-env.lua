setmetatable(_ENV, {__index = function(_, k) error("undefined " .. k) end})
function on_block(text) return text .. undefined_name end
