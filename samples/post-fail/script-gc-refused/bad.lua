-- A finalizer would run with the count hook off, after the post's files are written.
local guard = setmetatable({}, {__gc = function() while true do end end})
