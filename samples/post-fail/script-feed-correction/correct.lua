-- A shop's "feed correction": every feed per revolution a quarter faster. The gate lets it
-- through (the block keeps its words and formats); the tool then feeds 0.25 mm/rev where the
-- CL asks for 0.2, which the comparison with the CL finds at the first cut.
function on_block(text)
  return (text:gsub("F(%d*%.%d+)", function(v) return string.format("F%.2f", tonumber(v) * 1.25) end))
end
