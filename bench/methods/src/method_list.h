// The built-in loop-closure methods, one line each, in report order: HOILCD_METHOD(Factory) names
// a function `std::unique_ptr<LoopClosureMethod> Factory()` defined in this folder. Adding a
// method is one new file here plus one line below (docs/guide/methods.md).
HOILCD_METHOD(MakeSlcdMethod)
HOILCD_METHOD(MakeDlcdMethod)
HOILCD_METHOD(MakeFusionMethod)
HOILCD_METHOD(MakeSlcdLoMethod)
HOILCD_METHOD(MakeDlcdLoMethod)
HOILCD_METHOD(MakeDlcdTrackMethod)
HOILCD_METHOD(MakeFusionTcMethod)
HOILCD_METHOD(MakeThumbMethod)
HOILCD_METHOD(MakeThumbSeqMethod)
HOILCD_METHOD(MakeDlcdOracleMethod)
HOILCD_METHOD(MakeSlcdIdealMethod)
