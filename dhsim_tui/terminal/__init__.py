"""Terminal plumbing below Textual: what the terminal can show (charset,
colours), the bytes written per frame, type-ahead and signals.
"""
