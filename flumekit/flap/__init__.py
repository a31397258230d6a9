"""flap"""
