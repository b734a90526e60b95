GOTO/1e999,nan,inf
GOTO/29.0,1e,2.0
