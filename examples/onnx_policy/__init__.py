"""An ONNX policy run by onnxruntime, served by nav2_pyif (README.md beside this file)."""
